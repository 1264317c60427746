// Typed errors. InputError: bad user input (exit status 2). OutputError, SimulationError: a
// failure part-way (exit 3).
#pragma once
#include <stdexcept>
#include <string>

namespace vdc {

// A text quoted in a message (a path, a token, a parser's complaint), cut to `most` characters:
// from hostile input it can be a whole file.
inline std::string shortened(const std::string& text, std::size_t most = 200) {
  if (text.size() <= most) return text;
  return text.substr(0, most) + "... (" + std::to_string(text.size()) + " characters)";
}

// Something the user gave us is wrong: names the file, the place in it and the problem.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, const std::string& place, const std::string& problem)
      : std::runtime_error(compose(file, place, problem)), file_(file), place_(place), problem_(problem) {}
  const std::string& file() const { return file_; }
  const std::string& place() const { return place_; }
  const std::string& problem() const { return problem_; }

 private:
  static std::string compose(const std::string& file, const std::string& place, const std::string& problem) {
    std::string s = shortened(file);  // a hostile path can be thousands of characters
    if (!place.empty()) s += (s.empty() ? "" : ":") + place;
    return s.empty() ? problem : s + ": " + problem;
  }
  std::string file_, place_, problem_;
};

// A result could not be written (a full disk, a directory taken away): names the file and the
// problem.
class OutputError : public std::runtime_error {
 public:
  OutputError(const std::string& file, const std::string& problem) : std::runtime_error(file + ": " + problem) {}
};

// A mesh topology request that would break an invariant (non-manifold edge, flipped orientation...).
class TopologyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The simulation could not go on even after its fallbacks.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace vdc
