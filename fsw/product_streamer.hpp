// ProductStreamer: downlinks products (left image, disparity and overlay
// thumbnails, point cloud, the proposals picture) as PRODUCT packets of 1024 data bytes, a few per
// cycle and only while the downlink queue has room beyond a reserve, so a
// large product never crowds out events and housekeeping. Each kind has its
// own buffer sized at init. A product of a kind still streaming is refused
// with PRODUCT_REFUSED (the one on its way is never cut short); one that does
// not fit its buffer too. PRODUCT_SENT is raised when a product's last chunk
// is queued.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/image_view.hpp"
#include "fsw/event_log.hpp"
#include "tlm/tlm_queue.hpp"

namespace petra::fsw {

enum class ProductKind : std::uint8_t {
  LEFT_IMAGE = 1,
  DISPARITY = 2,
  OVERLAY = 3,
  POINT_CLOUD = 4,
  PROPOSALS = 5  // the left image with the proposals drawn (fsw/proposal_picture)
};
enum class ProductFormat : std::uint8_t { GRAY8 = 1, RGB8 = 2, XYZ_F32 = 3 };
inline constexpr std::size_t kProductKinds = 5;
// The proposals picture is at most half the image's size a side.
inline constexpr int kProposalsPictureMinStep = 2;

class ProductStreamer {
 public:
  // memory[k]: buffer of kind k+1 (bytes_needed below). events: where
  // PRODUCT_SENT and PRODUCT_REFUSED go (none when null).
  void init(std::array<std::span<std::uint8_t>, kProductKinds> memory, EventLog* events = nullptr);

  // Buffer sizes for a budget.
  static std::array<std::size_t, kProductKinds> bytes_needed(int max_width, int max_height,
                                                             std::size_t cloud_points);

  // Copies an image subsampled by `step` (gray: channels 1, rgb: 3). False
  // (and PRODUCT_REFUSED) when that kind is still streaming or it does not fit.
  bool stage_image(ProductKind kind, std::uint32_t id, ImageView<const std::uint8_t> image,
                   int channels, int step);
  // Copies a gray image subsampled by `step` as RGB into the stream of `kind`
  // and returns it, writable until the next pump(), so the caller can draw
  // on it; an empty view (and PRODUCT_REFUSED) as stage_image refuses.
  ImageView<std::uint8_t> stage_gray_as_rgb(ProductKind kind, std::uint32_t id, ConstGray8View gray,
                                            int step);
  // Copies up to max_points points (uniformly subsampled) as big-endian f32.
  bool stage_cloud(std::uint32_t id, std::span<const float> xyz, std::size_t max_points);

  // Queues at most max_chunks chunks, keeping `reserve` queue slots free.
  void pump(tlm::TlmQueue& queue, tlm::TmTime time, std::size_t max_chunks, std::size_t reserve);
  bool idle() const;
  void cancel_all();
  std::uint32_t chunks_sent() const { return chunks_sent_; }
  std::uint32_t products_sent() const { return products_sent_; }
  std::uint32_t products_refused() const { return products_refused_; }

 private:
  struct Stream {
    std::span<std::uint8_t> buffer;
    std::size_t size = 0;
    std::uint32_t id = 0;
    std::uint16_t width = 0;
    std::uint16_t height = 0;
    ProductFormat format = ProductFormat::GRAY8;
    std::uint16_t chunks = 0;
    std::uint16_t next_chunk = 0;
    bool active = false;
  };
  enum class Refusal : std::int32_t { STREAMING = 1, TOO_LARGE = 2, EMPTY = 3 };
  // The stream of `kind`, or null (and PRODUCT_REFUSED) when it is busy.
  Stream* free_stream(ProductKind kind, std::uint32_t id);
  bool refuse(ProductKind kind, std::uint32_t id, Refusal why, std::uint32_t busy_id = 0);
  void finish(Stream& s);
  void open(Stream& s, std::uint32_t id, int w, int h, ProductFormat format, std::size_t bytes);

  std::array<Stream, kProductKinds> streams_{};
  EventLog* events_ = nullptr;
  std::size_t rr_ = 0;  // round robin between kinds
  std::uint32_t chunks_sent_ = 0;
  std::uint32_t products_sent_ = 0;
  std::uint32_t products_refused_ = 0;
};

}  // namespace petra::fsw
