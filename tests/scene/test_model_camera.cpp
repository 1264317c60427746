// Cameras from artists' files: Debian's test files' cameras where their nodes put them (the
// node's global transform composed by assimp's own matrix types), looking and rolled as the node
// turns the camera's view and up, with the field of view from the file's; a missing camera named.
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>

#include "core/error.hpp"
#include "scene/model_camera.hpp"
#include "support/text.hpp"

namespace vdc {
namespace {

const std::string kCameraModels = "/usr/share/assimp/models/";

aiMatrix4x4 node_global(const aiNode* n) {
  aiMatrix4x4 m;
  for (; n; n = n->mParent) m = n->mTransformation * m;
  return m;
}

Vec3 vec(const aiVector3D& v) { return Vec3(v.x, v.y, v.z); }

TEST(ModelCamera, TheTestFilesCamerasStandWhereTheirNodesPutThem) {
  struct Case {
    std::string file, camera;
    double metres;     // per unit of what the importer delivers
    double fov_y;      // degrees, from the file by hand
  };
  const double collada = 2 * std::atan(std::tan(0.5 * 49.13434 * M_PI / 180) / 1.777778) * 180 / M_PI;
  const double fbx = 2 * std::atan(std::tan(0.5 * 0.691111) / 1.777778) * 180 / M_PI;
  for (const Case& k : {Case{"Collada/cameras.dae", "Camera", 1.0, collada}, Case{"FBX/animation_with_skeleton.fbx", "Camera", 0.01, fbx}}) {
    SCOPED_TRACE(k.file);
    const FileCamera got = read_file_camera(kCameraModels + k.file, k.camera, {}, Camera{});
    ASSERT_EQ(got.keys.size(), 1u);  // no clip moves these cameras
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(kCameraModels + k.file, 0);
    ASSERT_TRUE(scene);
    const aiCamera* cam = scene->mCameras[0];
    const aiMatrix4x4 g = node_global(scene->mRootNode->FindNode(cam->mName));
    aiMatrix3x3 turn(g);
    const Vec3 position = k.metres * vec(g * cam->mPosition);
    const Vec3 forward = vec(turn * cam->mLookAt).normalized(), up = vec(turn * cam->mUp).normalized();
    const CameraKey& key = got.keys[0];
    EXPECT_LT((key.position - position).norm(), 1e-5 * std::max(1.0, position.norm()));
    EXPECT_LT(((key.target - key.position).normalized() - forward).norm(), 1e-6);
    EXPECT_LT((*key.up - up).norm(), 1e-6);
    EXPECT_NEAR(got.lens.fov_y_degrees, k.fov_y, 1e-4);
    EXPECT_NEAR(got.lens.near, k.metres * cam->mClipPlaneNear, 1e-9);
  }
  // glTF: the camera at its node, looking down the node's -z; yfov 0.7 radians as the file says.
  const FileCamera gltf = read_file_camera(kCameraModels + "glTF2/cameras/Cameras.gltf", "nodes[1]", {}, Camera{});
  EXPECT_LT((gltf.keys[0].position - Vec3(0.5, 0.5, 3)).norm(), 1e-6);
  EXPECT_LT((gltf.keys[0].target - Vec3(0.5, 0.5, 2)).norm(), 1e-6);
  EXPECT_NEAR(gltf.lens.fov_y_degrees, 0.7 * 180 / M_PI, 1e-4);
}

TEST(ModelCamera, AMissingCameraIsNamedWithTheOnesThereAre) {
  auto error = [](const std::string& file, const std::string& name) {
    try {
      read_file_camera(kCameraModels + file, name, {}, Camera{});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_TRUE(test::contains(error("Collada/cameras.dae", "Wide"), "no camera named 'Wide' (its cameras: 'Camera', 'Camera_002', 'Camera_003')"));
  EXPECT_TRUE(test::contains(error("Collada/cameras.dae", ""), "the file has 3 cameras: name one"));
  EXPECT_TRUE(test::contains(error("glTF2/simple_skin/simple_skin.gltf", ""), "the file has no camera"));
  EXPECT_TRUE(test::contains(error("glTF2/cameras/Cameras.gltf", "nodes[2]"), "field of view"));  // an orthographic camera
}

}  // namespace
}  // namespace vdc
