#include "hal/can.hpp"

namespace petra::hal {

Status validate_frame(const CanFrame& frame) {
  if (frame.len > 8)
    return Error::make(Errc::invalid_argument, "can frame: length %u > 8", frame.len);
  const std::uint32_t mask = frame.extended ? CanFrame::kExtendedIdMask : CanFrame::kStandardIdMask;
  if ((frame.id & ~mask) != 0) {
    return Error::make(Errc::invalid_argument, "can frame: id 0x%X does not fit %s format",
                       frame.id, frame.extended ? "29-bit" : "11-bit");
  }
  return ok_status();
}

const char* can_bus_state_name(CanBusState state) {
  switch (state) {
    case CanBusState::error_active:
      return "error_active";
    case CanBusState::error_warning:
      return "error_warning";
    case CanBusState::error_passive:
      return "error_passive";
    case CanBusState::bus_off:
      return "bus_off";
  }
  return "unknown";
}

}  // namespace petra::hal
