#include "render/video_file.h"

#include <stdexcept>
#include <string>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace bsg::render {
namespace {

std::string av_message(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

}  // namespace

struct VideoFile::Codec {
  std::string path;
  int width = 0, height = 0;
  AVFormatContext* format = nullptr;
  AVCodecContext* encoder = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* scaler = nullptr;
  bool header_written = false;
  bool closed = false;
  int frames = 0;

  [[noreturn]] void fail(const std::string& what, int code) const {
    throw std::runtime_error("cannot write video '" + path + "': " + what +
                             (code < 0 ? " (" + av_message(code) + ")" : ""));
  }

  // Sends a frame (nullptr: flush) and writes every packet the encoder returns.
  void encode(AVFrame* input) {
    int result = avcodec_send_frame(encoder, input);
    if (result < 0) fail("encoding failed", result);
    while ((result = avcodec_receive_packet(encoder, packet)) >= 0) {
      // Every frame lasts one tick; without it the last frame gets duration 0
      // and demuxers that honour the edit list drop it.
      packet->duration = 1;
      av_packet_rescale_ts(packet, encoder->time_base, stream->time_base);
      packet->stream_index = stream->index;
      const int written = av_interleaved_write_frame(format, packet);
      if (written < 0) fail("writing failed", written);
    }
    if (result != AVERROR(EAGAIN) && result != AVERROR_EOF) fail("encoding failed", result);
  }

  ~Codec() {
    sws_freeContext(scaler);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&encoder);
    if (format != nullptr) {
      if (format->pb != nullptr) avio_closep(&format->pb);
      avformat_free_context(format);
    }
  }
};

VideoFile::VideoFile(const std::string& path, int width, int height, const VideoOptions& options)
    : codec_(std::make_unique<Codec>()) {
  Codec& c = *codec_;
  c.path = path;
  c.width = width;
  c.height = height;
  if (width < 1 || height < 1 || width > 8192 || height > 8192) {
    throw std::invalid_argument("video '" + path + "': size " + std::to_string(width) + "x" +
                                std::to_string(height) + " is not in [1, 8192]");
  }
  if (options.fps < 1 || options.fps > 1000) {
    throw std::invalid_argument("video '" + path + "': fps must be in [1, 1000], got " +
                                std::to_string(options.fps));
  }
  // libx264 prints its statistics through FFmpeg's log at every close: keep
  // errors only (FFmpeg's log level is one setting for the whole process).
  av_log_set_level(AV_LOG_ERROR);
  int result = avformat_alloc_output_context2(&c.format, nullptr, "mp4", path.c_str());
  if (result < 0) c.fail("no MP4 muxer", result);
  const char* encoder_name = options.lossless ? "libx264rgb" : "libx264";
  const AVCodec* h264 = avcodec_find_encoder_by_name(encoder_name);
  if (h264 == nullptr) h264 = avcodec_find_encoder(AV_CODEC_ID_H264);
  if (h264 == nullptr) c.fail("FFmpeg's libavcodec has no H.264 encoder (Debian's links libx264)", 0);
  c.stream = avformat_new_stream(c.format, nullptr);
  c.encoder = avcodec_alloc_context3(h264);
  c.frame = av_frame_alloc();
  c.packet = av_packet_alloc();
  if (c.stream == nullptr || c.encoder == nullptr || c.frame == nullptr || c.packet == nullptr) {
    c.fail("out of memory", 0);
  }
  // yuv420p needs even sizes: round up (the scaler stretches by at most a pixel).
  const bool subsampled = !options.lossless;
  c.encoder->width = subsampled ? (width + 1) / 2 * 2 : width;
  c.encoder->height = subsampled ? (height + 1) / 2 * 2 : height;
  c.encoder->pix_fmt = options.lossless ? AV_PIX_FMT_RGB24 : AV_PIX_FMT_YUV420P;
  c.encoder->time_base = AVRational{1, options.fps};
  c.encoder->framerate = AVRational{options.fps, 1};
  c.encoder->gop_size = options.fps;
  // No B-frames: frames leave the encoder in order, the MP4 needs no edit
  // list, and every player and decoder shows exactly the frames written.
  c.encoder->max_b_frames = 0;
  if (c.format->oformat->flags & AVFMT_GLOBALHEADER) c.encoder->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  AVDictionary* settings = nullptr;
  av_dict_set(&settings, "preset", "veryfast", 0);
  av_dict_set(&settings, options.lossless ? "qp" : "crf", options.lossless ? "0" : "18", 0);
  // One thread: frames are small, and a rendering process keeps its cores for stepping.
  av_dict_set(&settings, "threads", "1", 0);
  result = avcodec_open2(c.encoder, h264, &settings);
  av_dict_free(&settings);
  if (result < 0) c.fail(std::string("cannot open the ") + h264->name + " encoder", result);
  result = avcodec_parameters_from_context(c.stream->codecpar, c.encoder);
  if (result < 0) c.fail("bad encoder parameters", result);
  c.stream->time_base = c.encoder->time_base;
  result = avio_open(&c.format->pb, path.c_str(), AVIO_FLAG_WRITE);
  if (result < 0) c.fail("cannot open the file", result);
  result = avformat_write_header(c.format, nullptr);
  if (result < 0) c.fail("cannot write the header", result);
  c.header_written = true;
  c.frame->format = c.encoder->pix_fmt;
  c.frame->width = c.encoder->width;
  c.frame->height = c.encoder->height;
  result = av_frame_get_buffer(c.frame, 0);
  if (result < 0) c.fail("out of memory", result);
  c.scaler = sws_getContext(width, height, AV_PIX_FMT_RGB24, c.encoder->width, c.encoder->height,
                            c.encoder->pix_fmt, SWS_BICUBIC, nullptr, nullptr, nullptr);
  if (c.scaler == nullptr) c.fail("no RGB conversion", 0);
}

VideoFile::~VideoFile() {
  if (!codec_->closed && codec_->header_written) {
    try {
      close();
    } catch (const std::exception&) {
      // A destructor must not throw; close() reports errors to callers that ask.
    }
  }
}

void VideoFile::add_frame(const Image& image) {
  Codec& c = *codec_;
  if (image.width != c.width || image.height != c.height) {
    throw std::invalid_argument("video '" + c.path + "': frame is " + std::to_string(image.width) +
                                "x" + std::to_string(image.height) + ", the video " +
                                std::to_string(c.width) + "x" + std::to_string(c.height));
  }
  if (c.closed) throw std::logic_error("video '" + c.path + "': add_frame after close");
  const int result = av_frame_make_writable(c.frame);
  if (result < 0) c.fail("out of memory", result);
  const std::uint8_t* source[1] = {image.rgb.data()};
  const int source_stride[1] = {image.width * 3};
  sws_scale(c.scaler, source, source_stride, 0, image.height, c.frame->data, c.frame->linesize);
  c.frame->pts = c.frames;
  c.encode(c.frame);
  ++c.frames;
}

void VideoFile::close() {
  Codec& c = *codec_;
  if (c.closed) return;
  c.closed = true;
  c.encode(nullptr);
  const int result = av_write_trailer(c.format);
  if (result < 0) c.fail("cannot write the trailer", result);
  if (avio_closep(&c.format->pb) < 0) c.fail("cannot close the file", 0);
}

int VideoFile::frames() const { return codec_->frames; }

}  // namespace bsg::render
