// Shared helpers of the renderer's tests: a renderer or a skip where no EGL
// driver exists, colour classes of the palette, PNG and MP4 reading through
// libpng and FFmpeg (independent of the code under test's writers).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}
#include <png.h>

#include "render/env_renderer.h"
#include "render/image.h"

namespace bsg::testing {

// A renderer, or nullptr after GTEST_SKIP where EGL cannot give a context
// (call with ASSERT_NO_FATAL_FAILURE and return when it is null).
inline std::unique_ptr<render::EnvRenderer> renderer_or_skip(const render::RenderOptions& options) {
  try {
    return std::make_unique<render::EnvRenderer>(options);
  } catch (const std::runtime_error& error) {
    if (std::string(error.what()).find("EGL") == std::string::npos) throw;
    return nullptr;
  }
}

#define BSG_RENDERER_OR_SKIP(name, options)                                      \
  auto name = ::bsg::testing::renderer_or_skip(options);                         \
  if (!name) GTEST_SKIP() << "no EGL driver on this machine: rendering untested"

// Colour classes of the palette (render/scene_renderer.cpp), lit or shaded.
inline bool is_agent_blue(const std::uint8_t* p) { return p[2] > 90 && p[2] > p[0] + 60 && p[2] > p[1] + 40; }
inline bool is_apple_green(const std::uint8_t* p) { return p[1] > 90 && p[1] > p[0] + 60 && p[1] > p[2] + 60; }
inline bool is_bomb_red(const std::uint8_t* p) { return p[0] > 90 && p[0] > p[1] + 60 && p[0] > p[2] + 60; }

inline int count_pixels(const render::Image& image, bool (*is)(const std::uint8_t*)) {
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) count += is(image.pixel(x, y)) ? 1 : 0;
  return count;
}

// Reads an 8-bit RGB PNG with libpng's simplified API.
inline render::Image read_png(const std::string& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) throw std::runtime_error("cannot read " + path);
  png.format = PNG_FORMAT_RGB;
  render::Image image;
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  image.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) {
    throw std::runtime_error("cannot decode " + path);
  }
  return image;
}

// Every frame of a video's first video stream, decoded to RGB.
inline std::vector<render::Image> decode_video(const std::string& path) {
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0) {
    throw std::runtime_error("cannot open " + path);
  }
  avformat_find_stream_info(format, nullptr);
  const AVCodec* codec = nullptr;
  const int stream = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (stream < 0) throw std::runtime_error("no video stream in " + path);
  AVCodecContext* decoder = avcodec_alloc_context3(codec);
  avcodec_parameters_to_context(decoder, format->streams[stream]->codecpar);
  avcodec_open2(decoder, codec, nullptr);
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  SwsContext* scaler = nullptr;
  std::vector<render::Image> frames;
  const auto receive = [&]() {
    while (avcodec_receive_frame(decoder, frame) >= 0) {
      render::Image& image = frames.emplace_back();
      image.width = frame->width;
      image.height = frame->height;
      image.rgb.resize(static_cast<size_t>(image.width * image.height * 3));
      scaler = sws_getCachedContext(scaler, frame->width, frame->height,
                                    static_cast<AVPixelFormat>(frame->format), frame->width,
                                    frame->height, AV_PIX_FMT_RGB24, SWS_POINT, nullptr, nullptr,
                                    nullptr);
      std::uint8_t* out[1] = {image.rgb.data()};
      const int stride[1] = {image.width * 3};
      sws_scale(scaler, frame->data, frame->linesize, 0, frame->height, out, stride);
    }
  };
  while (av_read_frame(format, packet) >= 0) {
    if (packet->stream_index == stream) {
      avcodec_send_packet(decoder, packet);
      receive();
    }
    av_packet_unref(packet);
  }
  avcodec_send_packet(decoder, nullptr);
  receive();
  sws_freeContext(scaler);
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&decoder);
  avformat_close_input(&format);
  return frames;
}

}  // namespace bsg::testing
