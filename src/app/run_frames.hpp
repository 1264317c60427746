// A run's written frames as `vdcloth render` and `vdcloth fidelity` draw them: the frames
// several runs have in common, one frame's meshes drawn through a camera with cloth told from
// bodies; and what these commands and `vdcloth check` write: output directories they can take
// back, tables written under a temporary name until complete.
#pragma once
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "output/run_output.hpp"
#include "render/rasterizer.hpp"

namespace vdc {

// A frame drawn: its pixels, and per mesh whether it is cloth (a garment) or a body and its
// frame file's name without the frame number (cloth_<garment>, obstacle_<name>).
struct DrawnFrame {
  RenderedFrame pixels;
  std::vector<char> cloth;
  std::vector<std::string> names;
};

// How the cloth is drawn: each garment in its own colour, or each face by its view factor (from
// the frame's PLY beside the OBJ; a run without one, fixed or adaptive, is at factor 1
// everywhere); with or without its mesh's edges.
struct DrawStyle {
  bool view_colours = false;
  bool wireframe = false;
};

// The frame's meshes through `camera` at `scale` times its image size; garments in colours given
// in name order (the same garment has the same colour in every run of a scene), bodies grey.
// Throws InputError naming a mesh file that cannot be read.
DrawnFrame draw_frame(const Camera& camera, const FrameFiles& files, double scale, const DrawStyle& style = {});

// The frames every one of `runs` has meshes for, in increasing order.
std::vector<int> frames_in_common(const std::vector<const std::map<int, FrameFiles>*>& runs);

// Creates `dir` (and its parents); returns the directories it had to make, deepest first, for
// a command that fails part-way to remove. Throws InputError when it cannot.
std::vector<std::filesystem::path> create_output_directory(const std::string& dir);

// A table written to PATH.partial and renamed to PATH by finish(), so that a command stopped
// part-way leaves no table that looks complete. Opening removes an earlier PATH; throws
// InputError when the file cannot be written.
class PartialTable {
 public:
  explicit PartialTable(std::string path);
  std::ofstream& stream() { return stream_; }
  void finish();   // closes and renames; InputError when it cannot
  void discard();  // closes and removes PATH.partial

 private:
  std::string path_;
  std::ofstream stream_;
};

}  // namespace vdc
