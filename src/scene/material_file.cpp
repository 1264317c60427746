#include "scene/material_file.hpp"

#include "io/json_reader.hpp"

namespace vdc {

Material parse_material(const JsonValue& j) {
  j.only_keys({"name", "source", "density", "stretch", "bending"});
  Material m;
  m.name = j.string_or("name", "");
  m.source = j.string_or("source", "");
  m.density = j.at("density").positive();
  JsonValue s = j.at("stretch");
  s.only_keys({"warp", "weft", "shear", "poisson"});
  m.warp = s.at("warp").positive();
  m.weft = s.at("weft").positive();
  m.shear = s.at("shear").positive();
  m.poisson = s.non_negative_or("poisson", 0.0);
  if (m.poisson >= 1.0) s.at("poisson").fail("must be below 1 (the energy would not be convex)");
  m.bending = j.at("bending").non_negative();
  return m;
}

Material load_material(const std::string& path) { return parse_material(JsonValue::load_file(path)); }

}  // namespace vdc
