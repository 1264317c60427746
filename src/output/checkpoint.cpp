#include "output/checkpoint.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/binary_io.hpp"
#include "core/error.hpp"

namespace vdc {

namespace {
const std::string kMagic = "vdcloth checkpoint";
constexpr uint32_t kFormat = 4;

// Calls take(data, n) on each block of a file in turn.
template <class Take>
void read_blocks(const std::string& path, Take&& take) {
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (!in) throw InputError(path, "", "cannot open");
  std::vector<char> block(1 << 20);
  std::size_t n = 0;
  while ((n = std::fread(block.data(), 1, block.size(), in)) > 0) take(block.data(), n);
  const bool failed = std::ferror(in) != 0;
  std::fclose(in);
  if (failed) throw InputError(path, "", "cannot read");
}

std::string read_bytes(const std::string& path) {
  std::string bytes;
  read_blocks(path, [&](const char* data, std::size_t n) { bytes.append(data, n); });
  return bytes;
}
}  // namespace

uint64_t file_hash(const std::string& path) {
  // Hashed block by block as it is read: the executable of a sanitizer build is a hundred
  // megabytes, and copying it whole through a stream iterator took seconds.
  uint64_t h = fnv1a64(nullptr, 0);
  read_blocks(path, [&](const char* data, std::size_t n) { h = fnv1a64(data, n, h); });
  return h;
}

uint64_t executable_hash() { return file_hash("/proc/self/exe"); }

std::string checkpoint_part(const Simulation& part) {
  BinaryWriter out;
  out.value<uint64_t>(part.scene().garments.size());
  for (std::size_t g = 0; g < part.scene().garments.size(); ++g) {
    out.string(part.scene().garments[g].name);
    part.garment_mesh(g).write_binary(out);
  }
  return out.bytes();
}

namespace {
ResumePoint read_part(BinaryReader& in, int frame) {
  ResumePoint point;
  point.frame = frame;
  const auto garments = in.value<uint64_t>();
  for (uint64_t g = 0; g < garments; ++g) {
    point.names.push_back(in.string());
    point.garments.push_back(Mesh::read_binary(in));
  }
  return point;
}
}  // namespace

ResumePoint read_checkpoint_part(const std::string& bytes, int frame, const std::string& source) {
  BinaryReader in(bytes.data(), bytes.size());
  try {
    ResumePoint point = read_part(in, frame);
    if (!in.at_end()) in.fail("unexpected bytes after the last garment");
    return point;
  } catch (const BinaryFormatError& e) {
    throw InputError(source, "byte " + std::to_string(e.offset()), e.problem());
  }
}

void write_checkpoint(const std::string& path, const Ensemble& run, const Checkpoint& c) {
  std::vector<std::string> parts;
  for (const auto& part : run.parts()) parts.push_back(checkpoint_part(*part));
  write_checkpoint(path, c, run.options().mode, run.frame(), parts);
}

void write_checkpoint(const std::string& path, const Checkpoint& c, SimMode mode, int frame, const std::vector<std::string>& parts) {
  BinaryWriter out;
  out.string(kMagic);
  out.value(kFormat);
  out.value(c.scene_hash);
  out.value(c.build_hash);
  out.value<int32_t>(c.checkpoint_every);
  out.value(c.perturbation.gravity);
  out.value(c.perturbation.resolution);
  out.string(sim_mode_name(mode));
  out.value<int32_t>(frame);
  out.value<int32_t>(c.segments);
  out.value(c.usage.wall_seconds);
  out.value(c.usage.cpu_seconds);
  out.value<int64_t>(c.usage.peak_kib);
  out.value<int64_t>(c.usage.machine.total);
  out.value<int64_t>(c.usage.machine.steal);
  out.value<uint64_t>(parts.size());
  for (const std::string& part : parts) out.raw(part.data(), part.size());
  const uint64_t sum = fnv1a64(out.bytes().data(), out.bytes().size());
  out.value(sum);

  const std::string tmp = path + ".tmp";
  std::FILE* file = std::fopen(tmp.c_str(), "wb");
  bool ok = file != nullptr && std::fwrite(out.bytes().data(), 1, out.bytes().size(), file) == out.bytes().size();
  ok = file != nullptr && std::fflush(file) == 0 && ok && ::fsync(::fileno(file)) == 0;
  if (file != nullptr && std::fclose(file) != 0) ok = false;
  std::error_code ec;
  if (ok) std::filesystem::rename(tmp, path, ec);
  if (!ok || ec) {
    std::filesystem::remove(tmp, ec);
    throw OutputError(path, std::string("cannot write: ") + (ok ? ec.message() : std::strerror(errno)));
  }
}

Checkpoint read_checkpoint(const std::string& path) {
  const std::string bytes = read_bytes(path);
  BinaryWriter magic;
  magic.string(kMagic);
  if (bytes.compare(0, magic.bytes().size(), magic.bytes()) != 0) throw InputError(path, "", "not a vdcloth checkpoint");
  if (bytes.size() < magic.bytes().size() + sizeof(uint64_t)) throw InputError(path, "", "too short to be a checkpoint");
  const std::size_t body = bytes.size() - sizeof(uint64_t);
  uint64_t stored = 0;
  std::memcpy(&stored, bytes.data() + body, sizeof stored);
  BinaryReader in(bytes.data(), body);
  Checkpoint c;
  try {
    in.string();  // the magic, checked above
    if (stored != fnv1a64(bytes.data(), body)) throw InputError(path, "", "damaged: its checksum does not match its contents");
    if (const auto format = in.value<uint32_t>(); format != kFormat)
      in.fail("checkpoint format " + std::to_string(format) + ", this vdcloth reads format " + std::to_string(kFormat));
    c.scene_hash = in.value<uint64_t>();
    c.build_hash = in.value<uint64_t>();
    c.checkpoint_every = in.value<int32_t>();
    c.perturbation.gravity = in.value<double>();
    c.perturbation.resolution = in.value<double>();
    c.mode = in.string();
    c.frame = in.value<int32_t>();
    c.segments = in.value<int32_t>();
    c.usage.wall_seconds = in.value<double>();
    c.usage.cpu_seconds = in.value<double>();
    c.usage.peak_kib = static_cast<long>(in.value<int64_t>());
    c.usage.machine.total = in.value<int64_t>();
    c.usage.machine.steal = in.value<int64_t>();
    if (c.frame < 0 || c.segments < 1 || c.segments > 1'000'000 || c.checkpoint_every < 1 || !std::isfinite(c.perturbation.gravity) ||
        !std::isfinite(c.perturbation.resolution))
      in.fail("frame " + std::to_string(c.frame) + ", segment " + std::to_string(c.segments) + ", interval " +
              std::to_string(c.checkpoint_every) + ", perturbations " + std::to_string(c.perturbation.gravity) + " and " +
              std::to_string(c.perturbation.resolution) + ": not a checkpoint's");
    const auto parts = in.value<uint64_t>();
    for (uint64_t p = 0; p < parts; ++p) c.parts.push_back(read_part(in, c.frame));
    if (!in.at_end()) in.fail("unexpected bytes after the last garment");
  } catch (const BinaryFormatError& e) {
    throw InputError(path, "byte " + std::to_string(e.offset()), e.problem());
  }
  return c;
}

}  // namespace vdc
