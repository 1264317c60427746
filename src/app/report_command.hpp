// `vdcloth report`: a folder that opens in a browser from disk and shows a run (beside another):
// a 3D viewer of its frames through the shot camera or an orbit camera, its stats as plots with
// the camera's cuts, its summary, check and log as tables.
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace vdc {

// Where Debian installs its JavaScript libraries (libjs-three, libjs-chart.js).
inline constexpr const char* kDebianJavascriptDir = "/usr/share/javascript";

// args: the options after `report`. Returns the exit status: 0 done, 2 bad usage or input.
// `javascript_dir`: where to find three.js and Chart.js.
int report_command(const std::vector<std::string>& args, std::ostream& out, const std::string& javascript_dir = kDebianJavascriptDir);

}  // namespace vdc
