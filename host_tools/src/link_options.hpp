// SPDX-License-Identifier: MIT
// The command-line options of the commands that talk to a controller over a serial line (`stream`,
// `jog`, `home`, `console`) or run one in their own process (`gpio`): where it is (--port,
// --baud), how long to wait for it (--link-timeout-ms) and whether operator keys come from a
// standard input that is no terminal (--keys). One place for their names, defaults and help.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace curvestep::host {

/// The controller's port and link.
struct ControllerLinkOptions {
  std::string port;                 ///< --port: serial port or pseudo-terminal
  int baud = 115200;                ///< --baud: real ports only
  unsigned link_timeout_ms = 3000;  ///< --link-timeout-ms: silence before the link counts as failed
};

/// Adds --port,-p (required), --baud and --link-timeout-ms to `command`.
void add_controller_link_options(CLI::App& command, ControllerLinkOptions& link);

/// Adds --link-timeout-ms alone (a command whose controller runs in its own process: `gpio`).
void add_link_timeout_option(CLI::App& command, unsigned& link_timeout_ms);

/// Adds --keys: read `keys` (their description, "Esc / Ctrl-X") from standard input even when it is no terminal.
void add_keys_option(CLI::App& command, bool& keys_from_stdin, const std::string& keys);

}  // namespace curvestep::host
