// `vdcloth render`: pictures of a run through its scene's camera, one PNG a frame, and with
// --compare, two runs of the same shot side by side with their pixel differences measured.
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace vdc {

// args: the options after `render`. Returns the exit status: 0 done, 2 bad usage or input.
int render_command(const std::vector<std::string>& args, std::ostream& out);

}  // namespace vdc
