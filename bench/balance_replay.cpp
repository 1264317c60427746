// Scaling on paper: a run's measured per-group, per-frame seconds (groups.csv of an MPI run)
// replayed through the balancer's own policy (dist/placement.hpp) for other numbers of
// processes, static placement against moves.
//
// Model: a frame takes the greatest load of its processes (the sum of their groups' measured
// seconds) plus the frame's exchange, the measured one times log2 of the processes (tree
// collectives); the balancer looks every --every frames (1: after every frame, as a run with
// the direct solver does; with an iterative solver it looks at checkpoints only), and a group
// it moves adds its faces times the measured rebuild seconds a face to its receiver's next
// frame. Checkpoints come every --checkpoint-every frames (by default as often as the balancer
// looks), where with --restart-seconds-per-face every process's next frame pays that much for
// each face it holds (its checkpoint parts made, its solvers restarted), whichever the policy,
// and with --checkpoint-seconds the frame waits that long more for the first process to write
// the file.
// Both start longest first by the groups' faces at the first frame; static placement never
// moves. Efficiency: the groups' seconds over processes times the replayed wall time. With
// --run-ahead the processes wait for each other only at checkpoints (the groups are
// independent between them): an interval between checkpoints takes the greatest sum of a
// process's seconds over it.
//
// usage: vdcloth_balance_replay RUN_DIR [--every K] [--checkpoint-every C] [--processes N]... [--seconds-per-face S]
//                               [--restart-seconds-per-face S] [--checkpoint-seconds S] [--exchange S] [--run-ahead]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dist/placement.hpp"

namespace {

struct Costs {
  std::vector<std::string> groups;
  std::vector<std::vector<double>> seconds;  // [frame][group]
  std::vector<std::vector<double>> faces;
};

Costs read_groups(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string line;
  std::getline(in, line);
  if (line.rfind("frame,group,process,faces,seconds", 0) != 0) throw std::runtime_error(path + ": not a groups.csv");
  Costs c;
  std::map<std::string, std::size_t> index;
  std::map<int, std::map<std::size_t, std::pair<double, double>>> rows;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string frame, group, process, faces, seconds;
    std::getline(s, frame, ',');
    std::getline(s, group, ',');
    std::getline(s, process, ',');
    std::getline(s, faces, ',');
    std::getline(s, seconds, ',');
    if (!index.count(group)) {
      index[group] = c.groups.size();
      c.groups.push_back(group);
    }
    rows[std::stoi(frame)][index[group]] = {std::stod(faces), std::stod(seconds)};
  }
  for (const auto& [frame, groups] : rows) {
    std::vector<double> f(c.groups.size(), 0.0), t(c.groups.size(), 0.0);
    for (const auto& [g, ft] : groups) {
      f[g] = ft.first;
      t[g] = ft.second;
    }
    c.faces.push_back(f);
    c.seconds.push_back(t);
  }
  return c;
}

struct Replay {
  double wall = 0, work = 0;
  int moves = 0;
  double efficiency(int n) const { return work / (n * wall); }
};

Replay replay(const Costs& c, int n, int every, int checkpoint_every, bool balance, double seconds_per_face, double restart_per_face,
              double checkpoint_seconds, double exchange, bool run_ahead) {
  std::vector<int> owner = vdc::place_longest_first(c.faces.front(), n);
  Replay r;
  std::vector<double> since(c.groups.size(), 0.0), moving(static_cast<std::size_t>(n), 0.0);
  int frames_since = 0;
  const double frame_exchange = n > 1 ? exchange * std::log2(static_cast<double>(n)) : 0.0;
  std::vector<double> load(static_cast<std::size_t>(n), 0.0);
  for (std::size_t f = 0; f < c.seconds.size(); ++f) {
    for (std::size_t p = 0; p < load.size(); ++p) load[p] += moving[p];
    std::fill(moving.begin(), moving.end(), 0.0);
    for (std::size_t g = 0; g < owner.size(); ++g) {
      load[static_cast<std::size_t>(owner[g])] += c.seconds[f][g];
      r.work += c.seconds[f][g];
      since[g] += c.seconds[f][g];
    }
    ++frames_since;
    const int frame = static_cast<int>(f) + 1;
    const bool checkpoint = frame % checkpoint_every == 0;
    // In step, every frame waits for the busiest process; running ahead, only checkpoints do.
    if (!run_ahead || checkpoint || f + 1 == c.seconds.size()) {
      r.wall += *std::max_element(load.begin(), load.end()) + frame_exchange;
      std::fill(load.begin(), load.end(), 0.0);
    }
    if (balance && frame % every == 0 && f + 1 < c.seconds.size()) {
      std::vector<double> per_frame(since.size()), cost(since.size());
      for (std::size_t g = 0; g < since.size(); ++g) {
        per_frame[g] = since[g] / frames_since;
        cost[g] = c.faces[f][g] * seconds_per_face;
      }
      const int ahead = std::min(every, static_cast<int>(c.seconds.size() - f - 1));
      for (const vdc::GroupMove& m : vdc::rebalance(owner, per_frame, cost, n, ahead)) {
        owner[static_cast<std::size_t>(m.group)] = m.to;
        moving[static_cast<std::size_t>(m.to)] += cost[static_cast<std::size_t>(m.group)];
        ++r.moves;
      }
      std::fill(since.begin(), since.end(), 0.0);
      frames_since = 0;
    }
    if (checkpoint && f + 1 < c.seconds.size()) {
      for (std::size_t g = 0; g < owner.size(); ++g) moving[static_cast<std::size_t>(owner[g])] += c.faces[f][g] * restart_per_face;
      r.wall += checkpoint_seconds;
    }
  }
  return r;
}

// Each frame placed anew, longest first, free of charge, on the seconds of the frame `lag`
// frames before it (the first frame's for the first ones). Lag 0: the bound no placement of
// whole groups beats; lag 1: what the last frame's seconds alone would give.
double placed_anew_efficiency(const Costs& c, int n, std::size_t lag) {
  double wall = 0, work = 0;
  for (std::size_t f = 0; f < c.seconds.size(); ++f) {
    const std::vector<double>& frame = c.seconds[f];
    const std::vector<int> owner = vdc::place_longest_first(c.seconds[f >= lag ? f - lag : 0], n);
    std::vector<double> load(static_cast<std::size_t>(n), 0.0);
    for (std::size_t g = 0; g < owner.size(); ++g) {
      load[static_cast<std::size_t>(owner[g])] += frame[g];
      work += frame[g];
    }
    wall += *std::max_element(load.begin(), load.end());
  }
  return work / (n * wall);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: vdcloth_balance_replay RUN_DIR [--every K] [--checkpoint-every C] [--processes N]... [--seconds-per-face S]"
                 " [--restart-seconds-per-face S] [--checkpoint-seconds S] [--exchange S] [--run-ahead]\n";
    return 2;
  }
  const std::string dir = argv[1];
  int every = 10, checkpoint_every = 0;
  std::vector<int> processes;
  double seconds_per_face = -1, restart_per_face = 0, checkpoint_seconds = 0, exchange = -1;
  bool run_ahead = false;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--run-ahead") {
      run_ahead = true;
      continue;
    }
    if (i + 1 >= argc) {
      std::cerr << "option " << a << " needs a value\n";
      return 2;
    }
    const std::string v = argv[++i];
    if (a == "--every") every = std::stoi(v);
    else if (a == "--checkpoint-every") checkpoint_every = std::stoi(v);
    else if (a == "--processes") processes.push_back(std::stoi(v));
    else if (a == "--seconds-per-face") seconds_per_face = std::stod(v);
    else if (a == "--restart-seconds-per-face") restart_per_face = std::stod(v);
    else if (a == "--checkpoint-seconds") checkpoint_seconds = std::stod(v);
    else if (a == "--exchange") exchange = std::stod(v);
    else {
      std::cerr << "unknown option " << a << "\n";
      return 2;
    }
  }
  if (processes.empty()) processes = {2, 8, 32, 128};
  try {
    const Costs c = read_groups(dir + "/groups.csv");
    // The run's own measures: the rebuild rate from summary.json, the exchange from ranks.csv
    // (each frame's least waiting: what even the busiest process waited).
    if (seconds_per_face < 0) {
      std::ifstream s(dir + "/summary.json");
      const nlohmann::json j = nlohmann::json::parse(s);
      seconds_per_face = j["distribution"].value("rebuild_seconds_per_face", 0.0);
    }
    if (exchange < 0) {
      std::ifstream ranks(dir + "/ranks.csv");
      std::string line;
      std::getline(ranks, line);
      std::map<int, double> least;
      while (std::getline(ranks, line)) {
        int frame = 0, process = 0, groups = 0, faces = 0;
        double busy = 0, waiting = 0, moving = 0;
        if (std::sscanf(line.c_str(), "%d,%d,%d,%d,%lf,%lf,%lf", &frame, &process, &groups, &faces, &busy, &waiting, &moving) != 7) continue;
        least[frame] = least.count(frame) ? std::min(least[frame], waiting) : waiting;
      }
      std::vector<double> w;
      for (const auto& [f, x] : least) w.push_back(x);
      std::sort(w.begin(), w.end());
      exchange = w.empty() ? 0.0 : w[w.size() / 2];
    }
    if (checkpoint_every <= 0) checkpoint_every = every;
    std::printf("%zu groups, %zu frames, balanced every %d frames, checkpoints every %d, rebuild %.3g s a face, restart %.3g s a face, checkpoint file %.3g s, exchange %.3g s a frame at 2 processes\n",
                c.groups.size(), c.seconds.size(), every, checkpoint_every, seconds_per_face, restart_per_face, checkpoint_seconds, exchange);
    if (run_ahead) std::printf("processes wait for each other only at checkpoints\n");
    std::printf("| processes | static efficiency | balanced efficiency | moves | each frame placed anew on the last frame's seconds, free | on its own seconds, free |\n"
                "| ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (int n : processes) {
      const Replay s = replay(c, n, every, checkpoint_every, false, seconds_per_face, restart_per_face, checkpoint_seconds, exchange, run_ahead);
      const Replay b = replay(c, n, every, checkpoint_every, true, seconds_per_face, restart_per_face, checkpoint_seconds, exchange, run_ahead);
      std::printf("| %d | %.1f%% | %.1f%% | %d | %.1f%% | %.1f%% |\n", n, 100 * s.efficiency(n), 100 * b.efficiency(n), b.moves,
                  100 * placed_anew_efficiency(c, n, 1), 100 * placed_anew_efficiency(c, n, 0));
    }
  } catch (const std::exception& e) {
    std::cerr << "vdcloth_balance_replay: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
