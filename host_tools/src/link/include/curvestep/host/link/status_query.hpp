// SPDX-License-Identifier: MIT
// read_status: connect to a controller and ask for one StatusReport (where the machine stands),
// e.g. before a jog, whose move must start at the controller's position; set_position: tell a
// standing controller its coordinates (homing), then read its StatusReport.
#pragma once

#include <curvestep/host/link/transport.hpp>
#include <curvestep/protocol/link_sender.hpp>
#include <curvestep/protocol/messages.hpp>

namespace curvestep::host::link {

/// Connects (a new session: it stops any job the controller runs) and returns its StatusReport.
/// Throws LinkError (LinkTimeout if no report comes within settings.link_timeout_ms) or TransportError.
[[nodiscard]] protocol::StatusReport read_status(Transport& transport, const protocol::SenderSettings& settings);

/// Connects, sends SetPosition `position` and returns the StatusReport that follows it. Throws
/// LinkError as read_status, and with the controller's code if it refuses the SetPosition.
[[nodiscard]] protocol::StatusReport set_position(Transport& transport, const protocol::SenderSettings& settings,
                                                  const protocol::SetPosition& position);

}  // namespace curvestep::host::link
