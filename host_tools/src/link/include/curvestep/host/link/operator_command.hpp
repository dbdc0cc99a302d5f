// SPDX-License-Identifier: MIT
// OperatorCommand: what the operator asks of a running job (keys, signals), as stream_job takes it.
#pragma once

#include <cstdint>

namespace curvestep::host::link {

/// One request from the operator (grbl's real-time commands: `!` hold, `~` resume, Ctrl-X abort, `?` status).
enum class OperatorCommand : std::uint8_t {
  None,    ///< nothing asked
  Hold,    ///< feed hold: brake to a stop on the path (FeedHold)
  Resume,  ///< continue after a hold (Resume)
  Abort,   ///< stop at once and end the job (Abort)
  Status,  ///< print one status line
};

}  // namespace curvestep::host::link
