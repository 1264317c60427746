// ASCII PLY writer with a per-face value.
#include "io/ply.hpp"

#include <vector>

#include "io/text_file.hpp"

namespace vdc {

bool write_ply_with_face_values(const Mesh& mesh, const std::string& path, const std::string& name, const std::string& attribute,
                                int decimals) {
  TextFile out(path);
  if (!out.ok()) return false;
  const auto& value = mesh.face_attrs().get<double>(attribute);
  std::vector<int32_t> index(static_cast<std::size_t>(mesh.node_capacity()), -1);
  int32_t n = 0;
  for (NodeId v : mesh.nodes()) index[static_cast<std::size_t>(v.idx)] = n++;
  out.text("ply\nformat ascii 1.0\nelement vertex ").integer(n).text("\nproperty double x\nproperty double y\nproperty double z\n");
  out.text("element face ").integer(mesh.num_faces()).text("\nproperty list uchar int vertex_indices\nproperty float ").text(name).text("\nend_header\n");
  auto coordinate = [&](double c) -> TextFile& { return decimals < 0 ? out.number(c) : out.fixed(c, decimals); };
  for (NodeId v : mesh.nodes()) {
    coordinate(mesh.x(v).x()).text(" ");
    coordinate(mesh.x(v).y()).text(" ");
    coordinate(mesh.x(v).z()).text("\n");
  }
  for (FaceId f : mesh.faces()) {
    out.text("3");
    for (int k = 0; k < 3; ++k) out.text(" ").integer(index[static_cast<std::size_t>(mesh.face_node(f, k).idx)]);
    out.text(" ").number(value[f], 6).text("\n");
  }
  return out.close();
}

}  // namespace vdc
