// BVH (Biovision hierarchy) motion files: a recursive-descent reader over line-numbered tokens.
#include "scene/bvh_motion.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/input_file.hpp"

namespace vdc {

namespace {

struct Token {
  std::string text;
  int line;
};

class Reader {
 public:
  Reader(const std::string& text, const std::string& name) : name_(name) {
    int line = 1;
    std::string cur;
    for (char ch : text) {
      if (ch == '\n' || ch == '\r' || ch == ' ' || ch == '\t') {
        if (!cur.empty()) tokens_.push_back({cur, line});
        cur.clear();
        if (ch == '\n') ++line;
      } else {
        cur += ch;
      }
    }
    if (!cur.empty()) tokens_.push_back({cur, line});
    last_line_ = line;
  }

  [[noreturn]] void fail(int line, const std::string& problem) const {
    throw InputError(name_, "line " + std::to_string(line), problem);
  }
  bool done() const { return pos_ >= tokens_.size(); }
  int line() const { return done() ? last_line_ : tokens_[pos_].line; }
  const Token& next(const std::string& what) {
    if (done()) fail(last_line_, "file ends where " + what + " was expected");
    return tokens_[pos_++];
  }
  const std::string& peek() const {
    static const std::string empty;
    return done() ? empty : tokens_[pos_].text;
  }
  // A name: the next token and the rest of its line up to a '{' ("Bip01 L Thigh").
  std::string name(const std::string& what) {
    const Token& first = next(what);
    std::string out = first.text;
    while (!done() && tokens_[pos_].line == first.line && tokens_[pos_].text != "{") out += " " + tokens_[pos_++].text;
    return out;
  }
  void expect(const std::string& word) {
    const Token& t = next("'" + word + "'");
    if (t.text != word) fail(t.line, "expected '" + word + "', found '" + t.text + "'");
  }
  double number(const std::string& what) {
    const Token& t = next(what);
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(t.text.c_str(), &end);
    if (end == t.text.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      fail(t.line, "expected " + what + ", found '" + t.text + "'");
    return v;
  }

 private:
  std::string name_;
  std::vector<Token> tokens_;
  std::size_t pos_ = 0;
  int last_line_ = 1;
};

Channel parse_channel(Reader& r) {
  const Token& t = r.next("a channel name");
  static const std::pair<const char*, Channel> kNames[] = {{"Xposition", Channel::XPosition}, {"Yposition", Channel::YPosition},
                                                           {"Zposition", Channel::ZPosition}, {"Xrotation", Channel::XRotation},
                                                           {"Yrotation", Channel::YRotation}, {"Zrotation", Channel::ZRotation}};
  for (const auto& [name, c] : kNames)
    if (t.text == name) return c;
  r.fail(t.line, "unknown channel '" + t.text + "' (expected X/Y/Z position or rotation)");
}

Vec3 parse_offset(Reader& r) {
  r.expect("OFFSET");
  Vec3 o;
  for (int i = 0; i < 3; ++i) o[i] = r.number("an OFFSET coordinate");
  return o;
}

// Joints nested deeper than this are refused (a body has about ten; a hostile file could nest
// enough to exhaust the stack of this recursive reader).
constexpr int kMaxJointDepth = 256;

// A joint's body after its name: { OFFSET, CHANNELS, children }, `depth` below the root.
void parse_joint(Reader& r, Skeleton& s, const std::string& name, int parent, int depth) {
  if (depth > kMaxJointDepth) r.fail(r.line(), "joints nested more than " + std::to_string(kMaxJointDepth) + " levels deep");
  r.expect("{");
  const int index = static_cast<int>(s.joints.size());
  s.joints.push_back(Joint{name, parent, Vec3::Zero(), {}, s.num_channels});
  s.joints.back().offset = parse_offset(r);
  if (r.peek() == "CHANNELS") {
    r.expect("CHANNELS");
    const int line = r.line();
    const double n = r.number("a channel count");
    if (n != std::floor(n) || n < 0 || n > 6) r.fail(line, "a joint has 0 to 6 channels");
    for (int i = 0; i < static_cast<int>(n); ++i) s.joints[static_cast<std::size_t>(index)].channels.push_back(parse_channel(r));
    s.num_channels += static_cast<int>(n);
  }
  while (r.peek() != "}") {
    const Token& t = r.next("JOINT, End Site or '}'");
    if (t.text == "JOINT") {
      parse_joint(r, s, r.name("a joint name"), index, depth + 1);
    } else if (t.text == "End") {
      r.expect("Site");
      r.expect("{");
      s.joints.push_back(Joint{name + "_end", index, parse_offset(r), {}, s.num_channels, true});
      r.expect("}");
    } else {
      r.fail(t.line, "expected JOINT, End Site or '}', found '" + t.text + "'");
    }
  }
  r.expect("}");
}

}  // namespace

Motion parse_bvh(const std::string& text, const std::string& name) {
  Reader r(text, name);
  Motion m;
  r.expect("HIERARCHY");
  r.expect("ROOT");
  parse_joint(r, m.skeleton, r.name("the root's name"), -1, 0);
  r.expect("MOTION");
  r.expect("Frames:");
  const int frames_line = r.line();
  const double frames = r.number("the frame count");
  if (frames != std::floor(frames) || frames < 1 || frames > 10'000'000) r.fail(frames_line, "the frame count must be a positive integer");
  r.expect("Frame");
  r.expect("Time:");
  const int time_line = r.line();
  m.frame_time = r.number("the frame time");
  if (!(m.frame_time > 0)) r.fail(time_line, "the frame time must be greater than 0");
  const auto channels = static_cast<std::size_t>(m.skeleton.num_channels);
  for (int f = 0; f < static_cast<int>(frames); ++f) {
    std::vector<double> values(channels);
    for (std::size_t c = 0; c < channels; ++c) {
      if (r.done()) r.fail(r.line(), "file ends in frame " + std::to_string(f + 1) + " of " + std::to_string(static_cast<int>(frames)));
      values[c] = r.number("a channel value");
    }
    m.frames.push_back(std::move(values));
  }
  // Files from motion-capture tools sometimes carry whole frames beyond the count in their
  // header: those are ignored (the header rules); anything else after the frames is an error.
  std::size_t extra = 0;
  const int extra_line = r.line();
  while (!r.done()) {
    r.number("a channel value");
    ++extra;
  }
  if (channels == 0 ? extra > 0 : extra % channels != 0)
    r.fail(extra_line, "more values than " + std::to_string(static_cast<int>(frames)) + " frames of " + std::to_string(channels) +
                           " channels, and not whole frames");
  return m;
}

Motion read_bvh(const std::string& path) {
  constexpr std::uintmax_t kMaxBvhBytes = std::uintmax_t{1} << 30;
  return parse_bvh(read_input_text(path, kMaxBvhBytes, "BVH"), path);
}

bool write_bvh(const Motion& motion, const std::string& path) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) return false;
  const auto& joints = motion.skeleton.joints;
  static const char* kChannelNames[] = {"Xposition", "Yposition", "Zposition", "Xrotation", "Yrotation", "Zrotation"};
  std::fprintf(out, "HIERARCHY\n");
  // Depth-first over the hierarchy, closing braces as the depth falls.
  std::vector<int> open;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const Joint& joint = joints[j];
    while (!open.empty() && open.back() != joint.parent) {
      std::fprintf(out, "%*s}\n", 2 * (static_cast<int>(open.size()) - 1), "");
      open.pop_back();
    }
    const int indent = 2 * static_cast<int>(open.size());
    const bool end_site = joint.end_site;
    if (joint.parent < 0) std::fprintf(out, "ROOT %s\n", joint.name.c_str());
    else if (end_site) std::fprintf(out, "%*sEnd Site\n", indent, "");
    else std::fprintf(out, "%*sJOINT %s\n", indent, "", joint.name.c_str());
    std::fprintf(out, "%*s{\n%*sOFFSET %.9g %.9g %.9g\n", indent, "", indent + 2, "", joint.offset.x(), joint.offset.y(), joint.offset.z());
    if (!end_site) {
      std::fprintf(out, "%*sCHANNELS %zu", indent + 2, "", joint.channels.size());
      for (Channel c : joint.channels) std::fprintf(out, " %s", kChannelNames[static_cast<int>(c)]);
      std::fprintf(out, "\n");
    }
    open.push_back(static_cast<int>(j));
  }
  while (!open.empty()) {
    std::fprintf(out, "%*s}\n", 2 * (static_cast<int>(open.size()) - 1), "");
    open.pop_back();
  }
  std::fprintf(out, "MOTION\nFrames: %zu\nFrame Time: %.9g\n", motion.frames.size(), motion.frame_time);
  for (const auto& f : motion.frames) {
    for (std::size_t c = 0; c < f.size(); ++c) std::fprintf(out, c ? " %.6f" : "%.6f", f[c]);
    std::fprintf(out, "\n");
  }
  return std::fclose(out) == 0;
}

}  // namespace vdc
