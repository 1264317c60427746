// `vdcloth check`: the frame-end invariant of a run, checked on its written meshes. For every
// frame, each garment against itself, every other garment and every obstacle, by the exact
// triangle-triangle test.
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace vdc {

// args: the options after `check`. Returns 0 when no frame has a crossing, 3 when one has
// (the crossings are listed), 2 on bad usage or input.
int check_command(const std::vector<std::string>& args, std::ostream& out);

}  // namespace vdc
