// ASCII PLY writer with a per-face value.
#include "io/ply.hpp"

#include <cstdio>
#include <vector>

namespace vdc {

bool write_ply_with_face_values(const Mesh& mesh, const std::string& path, const std::string& name, const std::string& attribute) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) return false;
  const auto& value = mesh.face_attrs().get<double>(attribute);
  std::vector<int32_t> index(static_cast<std::size_t>(mesh.node_capacity()), -1);
  int32_t n = 0;
  for (NodeId v : mesh.nodes()) index[static_cast<std::size_t>(v.idx)] = n++;
  std::fprintf(out, "ply\nformat ascii 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\n", n);
  std::fprintf(out, "element face %d\nproperty list uchar int vertex_indices\nproperty float %s\nend_header\n", mesh.num_faces(), name.c_str());
  for (NodeId v : mesh.nodes()) std::fprintf(out, "%.17g %.17g %.17g\n", mesh.x(v).x(), mesh.x(v).y(), mesh.x(v).z());
  for (FaceId f : mesh.faces())
    std::fprintf(out, "3 %d %d %d %.6g\n", index[static_cast<std::size_t>(mesh.face_node(f, 0).idx)],
                 index[static_cast<std::size_t>(mesh.face_node(f, 1).idx)], index[static_cast<std::size_t>(mesh.face_node(f, 2).idx)], value[f]);
  return std::fclose(out) == 0;
}

}  // namespace vdc
