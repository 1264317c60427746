#include "app/cli.hpp"

#include "app/check_command.hpp"
#include "app/fidelity_command.hpp"
#include "app/render_command.hpp"
#include "app/report_command.hpp"
#include "app/run_command.hpp"
#include "app/table1.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <new>
#include <optional>
#include <sstream>
#include <thread>

#include "core/error.hpp"
#include "output/camera_export.hpp"
#include "output/checkpoint.hpp"
#include "output/run_output.hpp"
#include "scene/scene.hpp"
#include "sim/ensemble.hpp"

namespace vdc {

namespace {

namespace fs = std::filesystem;

const char* kMainHelp =
    "vdcloth: view-dependent adaptive cloth simulation\n"
    "\n"
    "usage:\n"
    "  vdcloth run SCENE.json [options]   simulate a scene\n"
    "  vdcloth bench table1 [options]     Koh et al. 2014's Table 1 on the project's scenes\n"
    "  vdcloth render SCENE.json RUN_DIR  pictures of a run through the scene's camera; with\n"
    "                 [options]           --compare, two runs side by side and their differences\n"
    "  vdcloth fidelity SCENE.json RUN_DIR REFERENCE_DIR [options]\n"
    "                                     how like a reference run a run looks through the scene's\n"
    "                                     camera (silhouette overlap, wrinkle detail, popping),\n"
    "                                     judged shot by shot against the chaos floor\n"
    "  vdcloth report RUN_DIR [options]   a page to open in a browser: the run in 3D with a timeline,\n"
    "                                     its faces and seconds per frame plotted, its summary\n"
    "  vdcloth check RUN_DIR [--every N]  no garment crosses itself, another or a body at any\n"
    "                                     written frame (exact triangle tests)\n"
    "  vdcloth --help                     this text\n"
    "  vdcloth --version                  version\n"
    "\n"
    "`vdcloth COMMAND --help` lists a command's options. Exit status: 0 done, 2 bad input or usage,\n"
    "3 a failure part-way: a simulation that could not be recovered, results that could not be written,\n"
    "memory that ran out or an unexpected error (check: a crossing; fidelity: a failed verdict).\n";

const char* kBenchHelp =
    "usage: vdcloth bench table1 [options]\n"
    "\n"
    "Benchmarks made of whole runs. There is one: table1, Koh, Narain and O'Brien's Table 1 on the\n"
    "project's scenes (fixed, adaptive and view runs of karate, solo-dancer and dancers-10; faces\n"
    "and seconds per frame, speed-ups). `vdcloth bench table1 --help` gives its options. The\n"
    "micro-benchmarks of the build (build/bench/vdcloth_bench) are Google Benchmark's.\n";

}  // namespace

int parse_int_in(const std::string& option, const std::string& value, int lowest, int highest) {
  std::size_t used = 0;
  long long n = 0;
  try {
    n = std::stoll(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != value.size() || value.empty() || n < lowest || n > highest)
    throw UsageError(option + " expects a whole number from " + std::to_string(lowest) + " to " + std::to_string(highest) + ", got '" +
                     value + "'");
  return static_cast<int>(n);
}

int parse_positive_int(const std::string& option, const std::string& value) { return parse_int_in(option, value, 1, 1'000'000); }

double parse_number(const std::string& option, const std::string& value, double lowest, double highest) {
  std::size_t used = 0;
  double x = 0;
  try {
    x = std::stod(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != value.size() || value.empty() || !(x >= lowest && x <= highest)) {
    std::ostringstream range;
    range << lowest << " to " << highest;
    throw UsageError(option + " expects a number from " + range.str() + ", got '" + value + "'");
  }
  return x;
}

int run_cli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err, bool interactive) {
  try {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      (args.empty() ? err : out) << kMainHelp;
      return args.empty() ? kExitBadInput : kExitOk;
    }
    if (args[0] == "--version") {
      out << "vdcloth " << VDCLOTH_VERSION << "\n";
      return kExitOk;
    }
    if (args[0] == "bench") {
      if (args.size() >= 2 && (args[1] == "--help" || args[1] == "-h")) {
        out << kBenchHelp;
        return kExitOk;
      }
      if (args.size() < 2) throw UsageError("bench expects a benchmark name: table1");
      if (args[1] != "table1") throw UsageError("bench: unknown benchmark '" + args[1] + "' (there is table1)");
      return table1_command(std::vector<std::string>(args.begin() + 2, args.end()), out, err);
    }
    if (args[0] == "check") return check_command(std::vector<std::string>(args.begin() + 1, args.end()), out);
    if (args[0] == "render") return render_command(std::vector<std::string>(args.begin() + 1, args.end()), out);
    if (args[0] == "report") return report_command(std::vector<std::string>(args.begin() + 1, args.end()), out);
    if (args[0] == "fidelity") return fidelity_command(std::vector<std::string>(args.begin() + 1, args.end()), out);
    if (args[0] != "run") throw UsageError("unknown command '" + args[0] + "' (try vdcloth --help)");
    for (std::size_t i = 1; i < args.size(); ++i)
      if (args[i] == "--help" || args[i] == "-h") {
        out << kRunHelp;
        return kExitOk;
      }
    return run_command(parse_run_args(args), out, err, interactive);
  } catch (const UsageError& e) {
    err << "vdcloth: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const InputError& e) {
    err << "vdcloth: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const SimulationError& e) {
    err << "vdcloth: simulation failed: " << e.what() << "\n";
    return kExitSimulationFailed;
  } catch (const OutputError& e) {
    err << "vdcloth: writing the results failed: " << e.what() << "\n";
    return kExitSimulationFailed;
  } catch (const std::bad_alloc&) {
    err << "vdcloth: out of memory: an allocation failed\n";
    return kExitSimulationFailed;
  } catch (const std::exception& e) {
    err << "vdcloth: unexpected error: " << e.what() << "\n";
    return kExitSimulationFailed;
  }
}

}  // namespace vdc
