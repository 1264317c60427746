// Pictures as a video people can watch: frames piped as raw RGB to Debian's ffmpeg, which
// encodes them as H.264 in an MP4 (yuv420p, padded to even sizes, so any player opens it).
#pragma once
#include <sys/types.h>

#include <string>

#include "io/png.hpp"

namespace vdc {

// Whether `ffmpeg` can be started from the PATH.
bool ffmpeg_available();

class VideoWriter {
 public:
  // Starts ffmpeg writing `path` from frames of `width` x `height` at `fps`. Throws OutputError
  // when it cannot be started.
  VideoWriter(std::string path, int width, int height, double fps);
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;
  ~VideoWriter();  // a writer not finished stops ffmpeg and leaves no file
  // The next frame, of the size given. Throws OutputError when ffmpeg has stopped.
  void add(const RgbImage& frame);
  // Ends the stream and waits for ffmpeg; OutputError when it did not encode the video.
  void finish();

 private:
  void stop();
  std::string path_;
  int width_, height_;
  int pipe_ = -1;
  pid_t child_ = -1;
};

}  // namespace vdc
