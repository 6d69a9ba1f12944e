#include "sim/calib/board_images.hpp"

#include "sim/calib/format_text.hpp"
#include "sim/calib/image_pairs.hpp"
#include "sim/io/image_io.hpp"

namespace petra::calib {

namespace {

// Corners of one image, or empty with a rejection recorded.
std::vector<Eigen::Vector2d> corners_of(const std::string& path, const ChessboardOptions& board,
                                        int& width, int& height, BoardImages& out) {
  auto img = io::read_gray_image(path);
  if (!img) {
    out.rejected.push_back({path, img.error().message});
    return {};
  }
  if (width == 0) {
    width = img->width;
    height = img->height;
  } else if (img->width != width || img->height != height) {
    out.rejected.push_back({path, format_text("image is %dx%d, the camera's first image %dx%d",
                                              img->width, img->height, width, height)});
    return {};
  }
  auto found = detect_chessboard(img->view(), board);
  if (!found) {
    out.rejected.push_back({path, found.error().message});
    return {};
  }
  if (!found->orientation_unique) out.orientation_unique = false;
  return found->uv;
}

}  // namespace

Result<BoardImages> find_boards(const std::string& left_pattern, const std::string& right_pattern,
                                const ChessboardOptions& board) {
  auto pairing = pair_images(left_pattern, right_pattern);
  if (!pairing) return pairing.error();
  BoardImages out;
  for (const std::string& p : pairing->unpaired)
    out.rejected.push_back({p, "no image of the other camera with the same name part"});
  for (const ImagePair& p : pairing->pairs) {
    StereoPairCorners c;
    c.left_name = p.left;
    c.right_name = p.right;
    c.left_uv = corners_of(p.left, board, out.left_width, out.left_height, out);
    c.right_uv = corners_of(p.right, board, out.right_width, out.right_height, out);
    out.pairs.push_back(std::move(c));
  }
  if (out.left_width == 0)
    return Error::make(Errc::io_error, "no readable image matches '%s'", left_pattern.c_str());
  if (out.right_width == 0)
    return Error::make(Errc::io_error, "no readable image matches '%s'", right_pattern.c_str());
  return out;
}

}  // namespace petra::calib
