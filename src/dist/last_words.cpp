#include "dist/last_words.hpp"

#include <pthread.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>

namespace vdc {

struct LastWords::Words {
  std::mutex mutex;
  std::string summary_path, log_path, where;
  nlohmann::json summary;
};

namespace {
sigset_t stop_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (int s : {SIGTERM, SIGINT, SIGHUP}) sigaddset(&set, s);
  return set;
}
}  // namespace

LastWords::LastWords() : words_(std::make_shared<Words>()) {
  const sigset_t set = stop_signals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::thread([words = words_, set] {
    int signal = 0;
    if (sigwait(&set, &signal) != 0) return;
    std::lock_guard<std::mutex> lock(words->mutex);
    const std::string why = std::string("stopped by signal ") + std::to_string(signal) + " (" + strsignal(signal) +
                            "): another process of the run ended, or the run was stopped";
    if (!words->summary_path.empty()) {
      words->summary["status"] = "failed";
      words->summary["error"] = why;
      std::ofstream(words->summary_path) << words->summary.dump(2) << "\n";
    }
    if (!words->log_path.empty()) std::ofstream(words->log_path, std::ios::app) << why << words->where << "\n";
    std::cerr << "vdcloth: " << why << words->where << std::endl;
    _exit(3);
  }).detach();
}

void LastWords::leave(const std::string& summary_path, nlohmann::json summary, const std::string& log_path, const std::string& where) {
  std::lock_guard<std::mutex> lock(words_->mutex);
  words_->summary_path = summary_path;
  words_->summary = std::move(summary);
  words_->log_path = log_path;
  words_->where = where;
}

}  // namespace vdc
