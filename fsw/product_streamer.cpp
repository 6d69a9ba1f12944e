#include "fsw/product_streamer.hpp"

#include <bit>
#include <cstring>

namespace petra::fsw {

namespace {
constexpr std::size_t kChunk = PETRA_PRODUCT_DATA_BYTES;
}

void ProductStreamer::init(std::array<std::span<std::uint8_t>, kProductKinds> memory,
                           EventLog* events) {
  for (std::size_t k = 0; k < kProductKinds; ++k) streams_[k] = Stream{memory[k]};
  events_ = events;
}

bool ProductStreamer::refuse(ProductKind kind, std::uint32_t id, Refusal why,
                             std::uint32_t busy_id) {
  ++products_refused_;
  if (events_ != nullptr)
    events_->raise(EventId::PRODUCT_REFUSED, static_cast<std::int32_t>(kind),
                   static_cast<std::int32_t>(id), static_cast<std::int32_t>(why),
                   static_cast<std::int32_t>(busy_id));
  return false;
}

ProductStreamer::Stream* ProductStreamer::free_stream(ProductKind kind, std::uint32_t id) {
  Stream& s = streams_[static_cast<std::size_t>(kind) - 1];
  if (!s.active) return &s;
  (void)refuse(kind, id, Refusal::STREAMING, s.id);
  return nullptr;
}

void ProductStreamer::finish(Stream& s) {
  s.active = false;
  ++products_sent_;
  if (events_ != nullptr)
    events_->raise(EventId::PRODUCT_SENT, static_cast<std::int32_t>((&s - streams_.data()) + 1),
                   static_cast<std::int32_t>(s.id), s.chunks, static_cast<std::int32_t>(s.size));
}

std::array<std::size_t, kProductKinds> ProductStreamer::bytes_needed(int max_width, int max_height,
                                                                     std::size_t cloud_points) {
  const auto pixels = static_cast<std::size_t>(max_width) * static_cast<std::size_t>(max_height);
  const int pw = (max_width + kProposalsPictureMinStep - 1) / kProposalsPictureMinStep;
  const int ph = (max_height + kProposalsPictureMinStep - 1) / kProposalsPictureMinStep;
  const std::size_t picture = 3 * static_cast<std::size_t>(pw) * static_cast<std::size_t>(ph);
  return {pixels, pixels, 3 * pixels, 12 * cloud_points, picture};
}

void ProductStreamer::open(Stream& s, std::uint32_t id, int w, int h, ProductFormat format,
                           std::size_t bytes) {
  s.size = bytes;
  s.id = id;
  s.width = static_cast<std::uint16_t>(w);
  s.height = static_cast<std::uint16_t>(h);
  s.format = format;
  s.chunks = static_cast<std::uint16_t>((bytes + kChunk - 1) / kChunk);
  s.next_chunk = 0;
  s.active = true;
}

bool ProductStreamer::stage_image(ProductKind kind, std::uint32_t id,
                                  ImageView<const std::uint8_t> image, int channels, int step) {
  if (step < 1 || channels < 1) return refuse(kind, id, Refusal::EMPTY);
  Stream* free = free_stream(kind, id);
  if (free == nullptr) return false;
  Stream& s = *free;
  const int pixels_w = image.width() / channels;
  const int w = (pixels_w + step - 1) / step;
  const int h = (image.height() + step - 1) / step;
  const auto bytes = static_cast<std::size_t>(w) * static_cast<std::size_t>(h) *
                     static_cast<std::size_t>(channels);
  if (bytes == 0) return refuse(kind, id, Refusal::EMPTY);
  if (bytes > s.buffer.size() || bytes > 0xFFFFu * kChunk)
    return refuse(kind, id, Refusal::TOO_LARGE);
  std::size_t o = 0;
  for (int y = 0; y < image.height(); y += step) {
    const std::uint8_t* row = image.row(y);
    for (int x = 0; x < pixels_w; x += step)
      for (int c = 0; c < channels; ++c) s.buffer[o++] = row[x * channels + c];
  }
  open(s, id, w, h, channels == 3 ? ProductFormat::RGB8 : ProductFormat::GRAY8, bytes);
  return true;
}

ImageView<std::uint8_t> ProductStreamer::stage_gray_as_rgb(ProductKind kind, std::uint32_t id,
                                                           ConstGray8View gray, int step) {
  if (step < 1) {
    (void)refuse(kind, id, Refusal::EMPTY);
    return {};
  }
  Stream* free = free_stream(kind, id);
  if (free == nullptr) return {};
  Stream& s = *free;
  const int w = (gray.width() + step - 1) / step;
  const int h = (gray.height() + step - 1) / step;
  const std::size_t bytes = 3 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  if (bytes == 0 || bytes > s.buffer.size() || bytes > 0xFFFFu * kChunk) {
    (void)refuse(kind, id, bytes == 0 ? Refusal::EMPTY : Refusal::TOO_LARGE);
    return {};
  }
  std::size_t o = 0;
  for (int y = 0; y < gray.height(); y += step) {
    const std::uint8_t* row = gray.row(y);
    for (int x = 0; x < gray.width(); x += step)
      for (int c = 0; c < 3; ++c) s.buffer[o++] = row[x];
  }
  open(s, id, w, h, ProductFormat::RGB8, bytes);
  return ImageView<std::uint8_t>(s.buffer.data(), 3 * w, h);
}

bool ProductStreamer::stage_cloud(std::uint32_t id, std::span<const float> xyz,
                                  std::size_t max_points) {
  Stream* free = free_stream(ProductKind::POINT_CLOUD, id);
  if (free == nullptr) return false;
  Stream& s = *free;
  const std::size_t points = xyz.size() / 3;
  std::size_t keep = points < max_points ? points : max_points;
  if (keep > s.buffer.size() / 12) keep = s.buffer.size() / 12;  // subsampled to fit
  if (keep > 0xFFFF) keep = 0xFFFF;
  if (keep == 0) return refuse(ProductKind::POINT_CLOUD, id, Refusal::EMPTY);
  std::size_t o = 0;
  for (std::size_t i = 0; i < keep; ++i) {
    const std::size_t src = i * points / keep;  // uniform subsampling
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t b =
          std::bit_cast<std::uint32_t>(xyz[3 * src + static_cast<std::size_t>(c)]);
      s.buffer[o++] = static_cast<std::uint8_t>(b >> 24);
      s.buffer[o++] = static_cast<std::uint8_t>(b >> 16);
      s.buffer[o++] = static_cast<std::uint8_t>(b >> 8);
      s.buffer[o++] = static_cast<std::uint8_t>(b);
    }
  }
  open(s, id, static_cast<int>(keep), 1, ProductFormat::XYZ_F32, o);
  return true;
}

void ProductStreamer::pump(tlm::TlmQueue& queue, tlm::TmTime time, std::size_t max_chunks,
                           std::size_t reserve) {
  for (std::size_t sent = 0; sent < max_chunks; ++sent) {
    if (queue.free_slots() <= reserve) return;
    Stream* s = nullptr;
    for (std::size_t k = 0; k < kProductKinds && s == nullptr; ++k) {
      Stream& c = streams_[(rr_ + k) % kProductKinds];
      if (c.active) s = &c;
    }
    if (s == nullptr) return;
    rr_ = (rr_ + 1) % kProductKinds;
    tlm::Product p;
    p.product = static_cast<std::uint8_t>((s - streams_.data()) + 1);
    p.format = static_cast<std::uint8_t>(s->format);
    p.id = s->id;
    p.chunk = s->next_chunk;
    p.chunks = s->chunks;
    p.total_bytes = static_cast<std::uint32_t>(s->size);
    p.width = s->width;
    p.height = s->height;
    const std::size_t at = static_cast<std::size_t>(s->next_chunk) * kChunk;
    const std::size_t n = s->size - at < kChunk ? s->size - at : kChunk;
    p.data_len = static_cast<std::uint16_t>(n);
    std::memcpy(p.data.data(), s->buffer.data() + at, n);
    wire::SeqFlags flags = wire::SeqFlags::continuation;
    if (s->chunks == 1)
      flags = wire::SeqFlags::unsegmented;
    else if (s->next_chunk == 0)
      flags = wire::SeqFlags::first;
    else if (s->next_chunk + 1 == s->chunks)
      flags = wire::SeqFlags::last;
    if (!queue.push(p, time, flags)) return;
    ++chunks_sent_;
    if (++s->next_chunk == s->chunks) finish(*s);
  }
}

bool ProductStreamer::idle() const {
  for (const Stream& s : streams_)
    if (s.active) return false;
  return true;
}

void ProductStreamer::cancel_all() {
  for (Stream& s : streams_) s.active = false;
}

}  // namespace petra::fsw
