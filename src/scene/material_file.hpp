// Materials as written in files: a JSON object (a file's top level or an inline block in a
// scene) with name, source, density, stretch {warp, weft, shear, poisson} and bending.
#pragma once
#include <string>

#include "physics/material.hpp"

namespace vdc {

class JsonValue;

// Reads a material from a JSON object. Throws InputError naming the key and the problem.
Material parse_material(const JsonValue& json);
Material load_material(const std::string& path);

}  // namespace vdc
