// Cameras from artists' files (model_camera.hpp).
#include "scene/model_camera.hpp"

#include <cmath>

#include "core/error.hpp"

namespace vdc {

namespace {

// The camera of that name (or the only one), with every camera's name.
const aiCamera& find_camera(const ModelFile& file, const std::string& name, std::vector<std::string>& names) {
  const aiScene& scene = file.scene();
  const aiCamera* found = nullptr;
  std::string listed;
  for (unsigned c = 0; c < scene.mNumCameras; ++c) {
    names.emplace_back(scene.mCameras[c]->mName.C_Str());
    listed += (c ? ", '" : "'") + names.back() + "'";
    if (names.back() == name) found = scene.mCameras[c];
  }
  if (scene.mNumCameras == 0) throw InputError(file.path(), "", "the file has no camera");
  if (name.empty() && scene.mNumCameras == 1) return *scene.mCameras[0];
  if (name.empty()) throw InputError(file.path(), "", "the file has " + std::to_string(scene.mNumCameras) + " cameras: name one (" + listed + ")");
  if (!found) throw InputError(file.path(), "", "no camera named '" + shortened(name) + "' (its cameras: " + listed + ")");
  return *found;
}

// The clip asked for, else the first that moves the node or a node above it.
const aiAnimation* camera_clip(const ModelFile& file, int node, const ClipChoice& choice) {
  if (!std::holds_alternative<std::monostate>(choice)) return file.clip(choice);
  for (unsigned a = 0; a < file.scene().mNumAnimations; ++a) {
    const std::vector<const aiNodeAnim*> channels = file.channels(file.scene().mAnimations[a]);
    for (int n = node; n >= 0; n = file.nodes().parent[static_cast<std::size_t>(n)])
      if (channels[static_cast<std::size_t>(n)]) return file.scene().mAnimations[a];
  }
  return nullptr;
}

}  // namespace

FileCamera read_file_camera(const std::string& path, const std::string& name, const ClipChoice& clip_choice, const Camera& lens) {
  const ModelFile file(path);
  FileCamera out;
  const aiCamera& cam = find_camera(file, name, out.names);
  const auto it = file.nodes().by_name.find(cam.mName.C_Str());
  if (it == file.nodes().by_name.end()) throw InputError(path, "camera '" + std::string(cam.mName.C_Str()) + "'", "no node carries it");
  const int node = it->second;
  // glTF's cameras sit at their node looking down its -z, y up; the importer's copy of the node's
  // translation in the camera's position would count it twice.
  const bool gltf = file.format().find("glTF") != std::string::npos;
  const Vec3 eye = gltf ? Vec3::Zero() : to_eigen(cam.mPosition);
  const Vec3 look = gltf ? Vec3(0, 0, -1) : to_eigen(cam.mLookAt), up = gltf ? Vec3(0, 1, 0) : to_eigen(cam.mUp);
  if (!(look.norm() > 0) || !(up.norm() > 0) || look.cross(up).norm() < 1e-9 * look.norm() * up.norm())
    throw InputError(path, "camera '" + std::string(cam.mName.C_Str()) + "'", "its view and up directions are zero or parallel");

  out.lens = lens;
  const double aspect = cam.mAspect > 0 ? cam.mAspect : static_cast<double>(lens.width) / lens.height;
  // The importers give glTF's vertical field of view times the aspect, the others' horizontal one.
  const double fov = gltf ? cam.mHorizontalFOV / aspect : 2 * std::atan(std::tan(0.5 * cam.mHorizontalFOV) / aspect);
  if (!(fov > 0 && fov < M_PI)) throw InputError(path, "camera '" + std::string(cam.mName.C_Str()) + "'", "its field of view is not between 0 and 180 degrees");
  out.lens.fov_y_degrees = fov * 180 / M_PI;
  const double metres = file.conversion().topLeftCorner<3, 3>().col(0).norm();
  if (cam.mClipPlaneNear > 0 && cam.mClipPlaneFar > cam.mClipPlaneNear) {
    out.lens.near = cam.mClipPlaneNear * metres;
    out.lens.far = cam.mClipPlaneFar * metres;
  }

  const aiAnimation* clip = camera_clip(file, node, clip_choice);
  const std::vector<double> ticks = clip ? file.sample_ticks(*clip) : std::vector<double>{0.0};
  const std::vector<const aiNodeAnim*> channels = file.channels(clip);
  for (double tick : ticks) {
    const Eigen::Matrix4d g = file.globals_at(channels, tick)[static_cast<std::size_t>(node)];
    const Mat3 linear = g.topLeftCorner<3, 3>();
    CameraKey key;
    key.time = clip ? (tick - ticks.front()) / ModelFile::ticks_per_second(*clip) : 0.0;
    key.position = (g * eye.homogeneous()).head<3>();
    key.target = key.position + (linear * look).normalized();
    key.up = (linear * up).normalized();
    if (!key.position.allFinite() || !key.target.allFinite() || !key.up->allFinite())
      throw InputError(path, "camera '" + std::string(cam.mName.C_Str()) + "'", "its pose is not finite at tick " + std::to_string(tick));
    out.keys.push_back(key);
  }
  return out;
}

}  // namespace vdc
