// `vdcloth fidelity`: how like a reference run (an adaptive run, say) a run of the same scene (a
// view run) looks through the scene's camera, frame by frame and shot by shot, judged against the
// chaos floor: the reference against a run of it perturbed below any physical meaning.
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace vdc {

// args: the options after `fidelity`. Returns the exit status: 0 every verdict passes, 3 one
// fails, 2 bad usage or input (found before anything is written).
int fidelity_command(const std::vector<std::string>& args, std::ostream& out);

}  // namespace vdc
