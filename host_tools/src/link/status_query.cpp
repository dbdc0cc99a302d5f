// SPDX-License-Identifier: MIT
#include <curvestep/host/link/status_query.hpp>

#include <optional>

#include <curvestep/host/link/host_link.hpp>

namespace curvestep::host::link {

protocol::StatusReport read_status(Transport& transport, const protocol::SenderSettings& settings) {
  HostLink link(transport, settings);
  std::optional<protocol::StatusReport> report;
  const auto handler = [&report](const protocol::Message& m) {
    if (m.type() == protocol::MessageType::StatusReport) report = m.get<protocol::StatusReport>();
  };
  link.connect(handler);
  report.reset();  // only the answer to this session's request
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
  return *report;
}

}  // namespace curvestep::host::link
