// Writes RGB frames as an MP4 file with H.264 video through FFmpeg's
// libraries (libavformat, libavcodec with libx264, libswscale).
//
// Parameters (VideoOptions):
//   fps       60: one frame per environment step of 1/60 s plays in real time
//   lossless  false: yuv420p at constant quality 18, which every player shows
//             (sizes are rounded up to even numbers, as 4:2:0 needs);
//             true: H.264 in RGB at quantiser 0 (libx264rgb), bit-exact
//             frames, for tests and analysis (fewer players show it)
#pragma once

#include <memory>
#include <string>

#include "render/image.h"

namespace bsg::render {

struct VideoOptions {
  int fps = 60;
  bool lossless = false;
};

class VideoFile {
 public:
  // Opens `path` and writes the header; throws std::runtime_error naming the
  // path (unwritable, no H.264 encoder) or std::invalid_argument for a bad size.
  VideoFile(const std::string& path, int width, int height, const VideoOptions& options = {});
  ~VideoFile();  // finishes the file if close() was not called (errors ignored)
  VideoFile(const VideoFile&) = delete;
  VideoFile& operator=(const VideoFile&) = delete;

  // Throws std::invalid_argument if the image is not width × height.
  void add_frame(const Image& image);
  // Flushes the encoder and writes the trailer; throws on a write error.
  void close();
  int frames() const;

 private:
  struct Codec;  // FFmpeg's objects
  std::unique_ptr<Codec> codec_;
};

}  // namespace bsg::render
