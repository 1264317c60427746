// Characters from artists' files: a two-bone glTF written here skins as linear blend skinning
// computed by hand; the rigged test models Debian ships skin as their own bone matrices (the
// file's node transforms and keys composed by assimp's matrix types, blended by hand) at the
// clip's key times; bad files are one-line input errors.
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/error.hpp"
#include "scene/rigged_model.hpp"
#include "scene/scene.hpp"
#include "support/text.hpp"
#include "support/temp_file.hpp"

namespace vdc {
namespace {

using test::temp_dir;

namespace fs = std::filesystem;

const std::string kModels = "/usr/share/assimp/models/";

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = static_cast<uint8_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<uint8_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= static_cast<uint8_t>(bytes[i + 2]);
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[v & 63] : '=';
  }
  return out;
}

// A two-bone strip, 0.5 m wide and 2 m tall: the hip bone at the origin, the knee bone 1 m up;
// rows at y = 0, 1, 2 weighted (1, 0), (0.5, 0.5) (or nothing), (0, 1); the clip turns the knee
// from nothing to 90 degrees about z over one second.
std::string two_bone_gltf(const fs::path& dir, bool middle_weighs = true) {
  std::string buffer;
  std::vector<std::pair<std::size_t, std::size_t>> views;  // offset, length
  auto add = [&](const void* data, std::size_t bytes) {
    while (buffer.size() % 4) buffer.push_back('\0');
    views.emplace_back(buffer.size(), bytes);
    buffer.append(static_cast<const char*>(data), bytes);
  };
  const float positions[] = {-0.25f, 0, 0, 0.25f, 0, 0, -0.25f, 1, 0, 0.25f, 1, 0, -0.25f, 2, 0, 0.25f, 2, 0};
  const uint8_t joints[] = {0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0};
  const float w = middle_weighs ? 0.5f : 0.0f;
  const float weights[] = {1, 0, 0, 0, 1, 0, 0, 0, w, w, 0, 0, w, w, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0};
  const uint16_t indices[] = {0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4};
  const float inverse_bind[] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  const float times[] = {0, 1};
  const float s = static_cast<float>(std::sqrt(0.5));
  const float turns[] = {0, 0, 0, 1, 0, 0, s, s};  // x, y, z, w
  add(positions, sizeof positions);
  add(joints, sizeof joints);
  add(weights, sizeof weights);
  add(indices, sizeof indices);
  add(inverse_bind, sizeof inverse_bind);
  add(times, sizeof times);
  add(turns, sizeof turns);
  std::string view_list;
  for (const auto& [offset, length] : views)
    view_list += (view_list.empty() ? "" : ", ") + std::string("{\"buffer\": 0, \"byteOffset\": ") + std::to_string(offset) +
                 ", \"byteLength\": " + std::to_string(length) + "}";
  const std::string text = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 2]}],
    "nodes": [{"name": "hip", "children": [1]}, {"name": "knee", "translation": [0, 1, 0]}, {"name": "strip", "mesh": 0, "skin": 0}],
    "skins": [{"joints": [0, 1], "inverseBindMatrices": 4}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2}, "indices": 3}]}],
    "animations": [{"name": "bend", "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}}],
                    "samplers": [{"input": 5, "output": 6, "interpolation": "LINEAR"}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [-0.25, 0, 0], "max": [0.25, 2, 0]},
      {"bufferView": 1, "componentType": 5121, "count": 6, "type": "VEC4"},
      {"bufferView": 2, "componentType": 5126, "count": 6, "type": "VEC4"},
      {"bufferView": 3, "componentType": 5123, "count": 12, "type": "SCALAR"},
      {"bufferView": 4, "componentType": 5126, "count": 2, "type": "MAT4"},
      {"bufferView": 5, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
      {"bufferView": 6, "componentType": 5126, "count": 2, "type": "VEC4"}],
    "bufferViews": [)" + view_list + R"(],
    "buffers": [{"byteLength": )" + std::to_string(buffer.size()) +
                           R"(, "uri": "data:application/octet-stream;base64,)" + base64(buffer) + R"("}]})";
  fs::create_directories(dir);
  const fs::path path = dir / "strip.gltf";
  std::ofstream(path) << text;
  return path.string();
}

// A scene whose one obstacle is the character block given.
Scene scene_with(const fs::path& dir, const std::string& character) {
  fs::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"({"garments": [{"name": "s", "mesh": {"grid": {"size": [0.2, 0.2], "cells": [1, 1]}},
    "transform": {"translate": [3, 0, 0]},
    "material": {"density": 0.1, "stretch": {"warp": 100, "weft": 100, "shear": 10}, "bending": 1e-6}}],
    "obstacles": [{"name": "c", "character": )" + character + "}]}";
  return load_scene((dir / "scene.json").string());
}

TEST(RiggedModel, ATwoBoneFileSkinsAsLinearBlendByHand) {
  const fs::path dir = temp_dir("rigged_strip");
  const std::string file = two_bone_gltf(dir);
  const Scene s = scene_with(dir, R"({"file": ")" + file + R"(", "recenter": false, "first_frame": 0})");
  fs::remove_all(dir);
  const ObstacleSpec& o = s.obstacles.at(0);
  ASSERT_TRUE(o.character);
  const std::vector<Vec3> rest = o.character->rest_mesh().positions;
  ASSERT_EQ(rest.size(), 6u);
  for (double t : {0.0, 0.25, 0.5, 1.0, 2.0}) {
    const double a = M_PI / 2 * std::min(t, 1.0), c = std::cos(a), sn = std::sin(a);
    const std::vector<Vec3> x = o.positions_at(t);
    for (std::size_t i = 0; i < rest.size(); ++i) {
      const double px = rest[i].x();
      Vec3 expected;
      if (rest[i].y() < 0.5) expected = Vec3(px, 0, 0);
      else if (rest[i].y() < 1.5) expected = 0.5 * Vec3(px, 1, 0) + 0.5 * Vec3(px * c, 1 + px * sn, 0);
      else expected = Vec3(px * c - sn, 1 + px * sn + c, 0);
      EXPECT_LT((x[i] - expected).norm(), 1e-6) << "t " << t << " vertex " << i;
    }
  }
}

// What assimp's own types make of a file at a clip tick where every channel has a key (or one
// only): per vertex, sum(w * global(bone) * offset * v) / sum(w), times `scale`.
std::vector<Vec3> file_skinning(const aiScene& scene, const aiAnimation& clip, double tick, double scale) {
  std::map<std::string, const aiNodeAnim*> channels;
  for (unsigned c = 0; c < clip.mNumChannels; ++c) channels[clip.mChannels[c]->mNodeName.C_Str()] = clip.mChannels[c];
  std::map<std::string, aiMatrix4x4> global;
  auto at = [&](const auto* keys, unsigned n) {
    for (unsigned k = 0; k < n; ++k)
      if (n == 1 || keys[k].mTime == tick) return keys[k].mValue;
    ADD_FAILURE() << "no key at " << tick;
    return keys[0].mValue;
  };
  auto walk = [&](auto& self, const aiNode* n, const aiMatrix4x4& parent) -> void {
    aiMatrix4x4 local = n->mTransformation;
    if (auto it = channels.find(n->mName.C_Str()); it != channels.end()) {
      const aiNodeAnim& ch = *it->second;
      local = aiMatrix4x4(at(ch.mScalingKeys, ch.mNumScalingKeys), at(ch.mRotationKeys, ch.mNumRotationKeys), at(ch.mPositionKeys, ch.mNumPositionKeys));
    }
    global[n->mName.C_Str()] = parent * local;
    for (unsigned c = 0; c < n->mNumChildren; ++c) self(self, n->mChildren[c], parent * local);
  };
  walk(walk, scene.mRootNode, aiMatrix4x4());
  std::vector<Vec3> out;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    std::vector<Vec3> sum(mesh.mNumVertices, Vec3::Zero());
    std::vector<double> total(mesh.mNumVertices, 0.0);
    for (unsigned b = 0; b < mesh.mNumBones; ++b) {
      const aiBone& bone = *mesh.mBones[b];
      const aiMatrix4x4 m4 = global.at(bone.mName.C_Str()) * bone.mOffsetMatrix;
      for (unsigned k = 0; k < bone.mNumWeights; ++k) {
        const aiVector3D p = m4 * mesh.mVertices[bone.mWeights[k].mVertexId];
        sum[bone.mWeights[k].mVertexId] += bone.mWeights[k].mWeight * Vec3(p.x, p.y, p.z);
        total[bone.mWeights[k].mVertexId] += bone.mWeights[k].mWeight;
      }
    }
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) out.push_back(scale * sum[v] / total[v]);
  }
  return out;
}

// The largest distance from a point of `a` to the nearest of `b` (a grid of cells `cell` wide).
double farthest_from(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double cell) {
  std::map<std::array<long, 3>, std::vector<Vec3>> grid;
  auto key = [&](const Vec3& p) { return std::array<long, 3>{std::lround(p.x() / cell), std::lround(p.y() / cell), std::lround(p.z() / cell)}; };
  for (const Vec3& p : b) grid[key(p)].push_back(p);
  double worst = 0;
  for (const Vec3& p : a) {
    double best = cell;
    const auto k = key(p);
    for (long i = -1; i <= 1; ++i)
      for (long j = -1; j <= 1; ++j)
        for (long l = -1; l <= 1; ++l)
          if (auto it = grid.find({k[0] + i, k[1] + j, k[2] + l}); it != grid.end())
            for (const Vec3& q : it->second) best = std::min(best, (p - q).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

TEST(RiggedModel, TheTestModelsSkinAsTheirOwnBoneMatrices) {
  struct Case {
    std::string file, clip;
    double scale, units;  // the scene's scale; metres per unit of what assimp delivers
  };
  for (const Case& k : {Case{"X/Testwuson.X", "Wuson_Walk", 0.5, 1.0}, Case{"FBX/animation_with_skeleton.fbx", "", 0.025, 0.01},
                        Case{"glTF2/simple_skin/simple_skin.gltf", "", 1.0, 1.0}}) {
    SCOPED_TRACE(k.file);
    const fs::path dir = temp_dir("rigged_models");
    const std::string clip = k.clip.empty() ? "" : R"(, "clip": ")" + k.clip + "\"";
    const Scene s = scene_with(dir, R"({"file": ")" + kModels + k.file + R"(", "recenter": false, "first_frame": 0, "scale": )" +
                                        std::to_string(k.scale) + clip + "}");
    fs::remove_all(dir);
    const ObstacleSpec& o = s.obstacles.at(0);
    Assimp::Importer importer;
    const aiScene* file = importer.ReadFile(kModels + k.file, aiProcess_Triangulate);
    ASSERT_TRUE(file);
    const aiAnimation* animation = file->mAnimations[0];
    for (unsigned a = 0; a < file->mNumAnimations; ++a)
      if (k.clip == file->mAnimations[a]->mName.C_Str()) animation = file->mAnimations[a];
    // Ticks at which every channel has a key; the clip's time 0 is its first key.
    double first = 1e300;
    const aiNodeAnim* longest = animation->mChannels[0];
    for (unsigned c = 0; c < animation->mNumChannels; ++c) {
      const aiNodeAnim& ch = *animation->mChannels[c];
      for (unsigned n = 0; n < ch.mNumRotationKeys; ++n) first = std::min(first, ch.mRotationKeys[n].mTime);
      for (unsigned n = 0; n < ch.mNumPositionKeys; ++n) first = std::min(first, ch.mPositionKeys[n].mTime);
      if (ch.mNumRotationKeys > longest->mNumRotationKeys) longest = &ch;
    }
    const double tps = animation->mTicksPerSecond > 0 ? animation->mTicksPerSecond : 25.0;
    double height = 0;
    {
      Aabb box;
      for (const Vec3& p : o.character->rest_mesh().positions) box.grow(p);
      height = (box.hi - box.lo).maxCoeff();
    }
    int compared = 0;
    for (unsigned n : {0u, longest->mNumRotationKeys / 2, longest->mNumRotationKeys - 1}) {
      const double tick = longest->mRotationKeys[n].mTime;
      bool everywhere = true;
      for (unsigned c = 0; c < animation->mNumChannels; ++c) {
        const aiNodeAnim& ch = *animation->mChannels[c];
        auto has = [&](const auto* keys, unsigned count) {
          if (count <= 1) return true;
          for (unsigned i = 0; i < count; ++i)
            if (keys[i].mTime == tick) return true;
          return false;
        };
        everywhere = everywhere && has(ch.mRotationKeys, ch.mNumRotationKeys) && has(ch.mPositionKeys, ch.mNumPositionKeys) &&
                     has(ch.mScalingKeys, ch.mNumScalingKeys);
      }
      if (!everywhere) continue;
      const std::vector<Vec3> expected = file_skinning(*file, *animation, tick, k.scale * k.units);
      const std::vector<Vec3> ours = o.positions_at((tick - first) / tps);
      const double tolerance = 1e-5 * height;
      EXPECT_LT(farthest_from(expected, ours, 1e-3 * height), tolerance) << "tick " << tick;
      EXPECT_LT(farthest_from(ours, expected, 1e-3 * height), tolerance) << "tick " << tick;
      ++compared;
    }
    EXPECT_GE(compared, 2);
  }
}

TEST(RiggedModel, BadFilesAreInputErrorsNamingTheProblem) {
  const fs::path dir = temp_dir("rigged_bad");
  const std::string strip = two_bone_gltf(dir);
  auto error = [&](const std::string& character) {
    try {
      scene_with(dir, character);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_TRUE(test::contains(error(R"({"file": ")" + strip + R"(", "clip": "run"})"), "no clip named 'run' (its clips: 'bend')"));
  EXPECT_TRUE(test::contains(error(R"({"file": ")" + strip + R"(", "clip": 3})"), "no clip 3 (the file has 1)"));
  std::ofstream(dir / "junk.fbx") << "this is no model";
  EXPECT_TRUE(test::contains(error(R"({"file": ")" + (dir / "junk.fbx").string() + R"("})"), "cannot read the file"));
  EXPECT_TRUE(test::contains(error(R"({"file": ")" + strip + R"(", "motion": "x.bvh"})"), "not both"));
  const std::string weightless = two_bone_gltf(dir / "weightless", false);
  EXPECT_TRUE(test::contains(error(R"({"file": ")" + weightless + R"("})"), "vertex 2 has no skinning weight"));
  EXPECT_TRUE(test::contains(error(R"({"file": ")" + strip + R"(", "scale": 10})"), "m tall with scale 10 (its skin's extent"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vdc

namespace vdc {
namespace {

// A Collada file that states centimetres and z up: a 170 cm post stands 1.7 m tall along y.
TEST(RiggedModel, AFileInCentimetresWithZUpStandsUpInMetres) {
  const fs::path dir = temp_dir("rigged_units");
  fs::create_directories(dir);
  std::ofstream(dir / "post.dae") << R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="centimeter" meter="0.01"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="post"><mesh>
    <source id="p"><float_array id="a" count="12">-20 -20 0 20 -20 0 0 20 0 0 0 170</float_array>
      <technique_common><accessor source="#a" count="4" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="4"><input semantic="VERTEX" source="#v" offset="0"/><p>0 2 1 0 1 3 1 2 3 2 0 3</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="post" name="post"><instance_geometry url="#post"/></node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>)";
  const RiggedModel post = read_rigged_model((dir / "post.dae").string());
  fs::remove_all(dir);
  Aabb box;
  for (const Vec3& x : post.skin.positions) box.grow(x);
  EXPECT_LT((box.lo - Vec3(-0.2, 0, -0.2)).norm(), 1e-6) << box.lo.transpose();
  EXPECT_LT((box.hi - Vec3(0.2, 1.7, 0.2)).norm(), 1e-6) << box.hi.transpose();
  EXPECT_EQ(post.motion.skeleton.joints.size(), 1u);  // a mesh without bones moves with its node
  EXPECT_EQ(post.motion.frames.size(), 1u);           // and without a clip stands still
}

}  // namespace
}  // namespace vdc
