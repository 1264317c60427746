#include "app/video_writer.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/error.hpp"

extern char** environ;

namespace vdc {

namespace {

// Spawns `args` (looked up in the PATH) with standard input from `input` (-1: /dev/null) and,
// when `quiet`, standard output and error to /dev/null. -1 when it cannot be started.
pid_t spawn(const std::vector<std::string>& args, int input, bool quiet) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (input >= 0) posix_spawn_file_actions_adddup2(&actions, input, 0);
  else posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  }
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int status = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return status == 0 ? pid : -1;
}

int wait_for(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

}  // namespace

bool ffmpeg_available() {
  const pid_t pid = spawn({"ffmpeg", "-version"}, -1, true);
  return pid > 0 && wait_for(pid) == 0;
}

VideoWriter::VideoWriter(std::string path, int width, int height, double fps) : path_(std::move(path)), width_(width), height_(height) {
  int ends[2];
  if (pipe2(ends, O_CLOEXEC) != 0) throw OutputError(path_, "cannot open a pipe to ffmpeg");
  child_ = spawn({"ffmpeg", "-y", "-nostdin", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
                  std::to_string(width) + "x" + std::to_string(height), "-framerate", number(fps), "-i", "pipe:0", "-vf",
                  "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-preset", "fast", "-crf", "18", "-pix_fmt", "yuv420p",
                  "-movflags", "+faststart", "-f", "mp4", path_},
                 ends[0], false);
  close(ends[0]);
  if (child_ < 0) {
    close(ends[1]);
    throw OutputError(path_, "cannot start ffmpeg (Debian package ffmpeg)");
  }
  pipe_ = ends[1];
}

void VideoWriter::add(const RgbImage& frame) {
  if (frame.width != width_ || frame.height != height_) throw std::logic_error("VideoWriter::add: a frame of another size");
  // A write to a pipe ffmpeg has closed raises SIGPIPE: blocked here, so the write fails with
  // EPIPE instead, and a signal left pending is taken before unblocking.
  sigset_t pipe_signal, before;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &before);
  const auto* data = frame.rgb.data();
  std::size_t left = frame.rgb.size();
  bool broken = false;
  while (left > 0 && !broken) {
    const ssize_t n = write(pipe_, data, left);
    if (n > 0) {
      data += n;
      left -= static_cast<std::size_t>(n);
    } else if (n < 0 && errno != EINTR) {
      broken = true;
    }
  }
  if (broken) {
    const timespec now{0, 0};
    sigtimedwait(&pipe_signal, nullptr, &now);
  }
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
  if (broken) throw OutputError(path_, "ffmpeg stopped taking frames");
}

void VideoWriter::finish() {
  close(pipe_);
  pipe_ = -1;
  const int status = wait_for(child_);
  child_ = -1;
  if (status != 0) {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
    throw OutputError(path_, "ffmpeg could not encode the video (exit status " + std::to_string(status) + ")");
  }
}

void VideoWriter::stop() {
  if (pipe_ >= 0) close(pipe_);
  pipe_ = -1;
  if (child_ > 0) {
    kill(child_, SIGTERM);
    wait_for(child_);
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  child_ = -1;
}

VideoWriter::~VideoWriter() { stop(); }

}  // namespace vdc
