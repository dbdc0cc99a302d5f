// SPDX-License-Identifier: MIT
#include <curvestep/host/link/host_link.hpp>

#include <array>
#include <random>

#include <curvestep/core/error_text.hpp>
#include <curvestep/protocol/frame.hpp>

namespace curvestep::host::link {

std::string describe_error(Error code) {
  return std::string(describe(code)) + " (" + std::string(error_name(code)) + ")";
}

HostLink::HostLink(Transport& transport, protocol::SenderSettings settings)
    : transport_(transport), sender_(settings), epoch_(std::chrono::steady_clock::now()) {}

std::uint32_t HostLink::now_ms() const noexcept {
  const auto elapsed = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - epoch_);
  return static_cast<std::uint32_t>(elapsed.count());
}

void HostLink::raise(const Failure& failure) const {
  std::string text = transport_.name() + ": link failed: " + describe_error(failure.code);
  if (failure.code == Error::RetransmitLimit) text += " (frame " + std::to_string(failure.index) + " never acknowledged)";
  if (failure.code == Error::LinkTimeout) text += ": the controller stopped answering";
  if (failure.code == Error::DeviceRestarted) text += ": the controller restarted and lost the session";
  throw LinkError(failure.code, text);
}

void HostLink::connect(const Handler& handler) {
  std::random_device random;
  sender_.connect(static_cast<std::uint16_t>(random()), now_ms());
  while (sender_.state() != protocol::LinkState::Connected) {
    pump(10, handler);
    if (sender_.state() == protocol::LinkState::Failed) raise(Failure{sender_.last_error(), no_index});
  }
}

void HostLink::submit(const protocol::Message& message) {
  const auto submitted = sender_.submit(message);
  if (!submitted) raise(submitted.failure());
}

void HostLink::transmit_due() {
  std::array<std::byte, protocol::max_encoded_frame_size> frame{};
  for (;;) {
    const auto size = sender_.poll(now_ms(), frame);
    if (!size) raise(size.failure());
    if (size.value() == 0) return;
    transport_.write(std::span<const std::byte>(frame.data(), size.value()));
    statistics_.bytes_sent += size.value();
  }
}

void HostLink::pump(int wait_ms, const Handler& handler) {
  transmit_due();
  std::array<std::byte, 512> bytes{};
  std::size_t count = transport_.read(bytes, wait_ms);
  while (count > 0) {
    for (std::size_t i = 0; i < count; ++i) {
      const auto pushed = decoder_.push(bytes[i]);
      if (!pushed) {
        ++statistics_.frames_rejected;
        continue;
      }
      if (!pushed.value()) continue;
      const auto message = protocol::decode_message(decoder_.frame());
      if (!message) {
        ++statistics_.frames_rejected;
        continue;
      }
      ++statistics_.frames_received;
      const auto handled = sender_.on_message(message.value(), now_ms());
      if (!handled) raise(handled.failure());
      const auto type = message.value().type();
      if (type != protocol::MessageType::Capabilities && type != protocol::MessageType::Ack &&
          type != protocol::MessageType::Nak && handler) {
        handler(message.value());
      }
    }
    count = transport_.read(bytes, 0);
  }
  transmit_due();
}

}  // namespace curvestep::host::link
