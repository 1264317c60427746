// Channel files (chan.hpp).
#include "io/chan.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "io/input_file.hpp"

namespace vdc {

std::vector<ChanFrame> parse_chan(const std::string& text, const std::string& name) {
  std::vector<ChanFrame> frames;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string place = "line " + std::to_string(number);
    std::istringstream fields(line);
    std::vector<double> v;
    std::string word;
    while (fields >> word) {
      if (v.empty() && word[0] == '#') break;
      std::size_t used = 0;
      double x = 0;
      try {
        x = std::stod(word, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != word.size() || !std::isfinite(x)) throw InputError(name, place, "'" + shortened(word, 40) + "' is not a finite number");
      v.push_back(x);
    }
    if (v.empty()) continue;
    if (v.size() != 7 && v.size() != 8)
      throw InputError(name, place, "expected 7 or 8 numbers (frame, translation, rotation and field of view), found " + std::to_string(v.size()));
    ChanFrame f;
    f.frame = v[0];
    f.translation = Vec3(v[1], v[2], v[3]);
    f.rotation_degrees = Vec3(v[4], v[5], v[6]);
    if (v.size() == 8) {
      if (!(v[7] > 0 && v[7] < 180)) throw InputError(name, place, "the field of view must be between 0 and 180 degrees");
      f.fov_y_degrees = v[7];
    }
    if (!frames.empty() && !(f.frame > frames.back().frame)) throw InputError(name, place, "frame numbers must increase");
    frames.push_back(f);
  }
  if (frames.empty()) throw InputError(name, "", "no frame in the channel file");
  return frames;
}

std::vector<ChanFrame> read_chan(const std::string& path) {
  constexpr std::uintmax_t kMaxChanBytes = 64u << 20;
  return parse_chan(read_input_text(path, kMaxChanBytes, "channel"), path);
}

}  // namespace vdc
