// SPDX-License-Identifier: MIT
#include <curvestep/host/link/status_query.hpp>

#include <optional>

#include <curvestep/host/link/host_link.hpp>

namespace curvestep::host::link {

namespace {

/// A new session: `command` (if any), then a StatusRequest; the StatusReport that answers it.
protocol::StatusReport command_then_status(Transport& transport, const protocol::SenderSettings& settings,
                                           const std::optional<protocol::Message>& command) {
  HostLink link(transport, settings);
  std::optional<protocol::StatusReport> report;
  std::optional<protocol::ErrorReport> refused;
  const auto handler = [&report, &refused](const protocol::Message& m) {
    if (m.type() == protocol::MessageType::StatusReport) report = m.get<protocol::StatusReport>();
    if (m.type() == protocol::MessageType::ErrorReport) refused = m.get<protocol::ErrorReport>();
  };
  link.connect(handler);
  report.reset();  // only the answer to this session's request
  refused.reset();
  if (command) link.submit(*command);
  link.submit(protocol::Message(protocol::StatusRequest{}));
  const std::uint32_t patience = settings.link_timeout_ms != 0 ? settings.link_timeout_ms : 3000;
  const std::uint32_t started = link.now_ms();
  while (!report || !link.idle()) {
    link.pump(5, handler);
    if (link.now_ms() - started > patience) {
      throw LinkError(Error::LinkTimeout, transport.name() + ": the controller did not answer a StatusRequest within " +
                                              std::to_string(patience) + " ms");
    }
  }
  if (command && refused) throw LinkError(refused->code, transport.name() + ": the controller refused it: " + describe_error(refused->code));
  return *report;
}

}  // namespace

protocol::StatusReport read_status(Transport& transport, const protocol::SenderSettings& settings) {
  return command_then_status(transport, settings, std::nullopt);
}

protocol::StatusReport set_position(Transport& transport, const protocol::SenderSettings& settings,
                                    const protocol::SetPosition& position) {
  return command_then_status(transport, settings, protocol::Message(position));
}

}  // namespace curvestep::host::link
