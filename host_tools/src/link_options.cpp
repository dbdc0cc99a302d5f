// SPDX-License-Identifier: MIT
#include "link_options.hpp"

namespace curvestep::host {

void add_controller_link_options(CLI::App& command, ControllerLinkOptions& link) {
  command.add_option("--port,-p", link.port, "Serial port or pseudo-terminal of the controller (/dev/ttyUSB0, /dev/pts/3)")->required();
  command.add_option("--baud", link.baud, "Baud rate (real ports)");
  add_link_timeout_option(command, link.link_timeout_ms);
}

void add_link_timeout_option(CLI::App& command, unsigned& link_timeout_ms) {
  command.add_option("--link-timeout-ms", link_timeout_ms, "Give up after this long without a word from the controller");
}

void add_keys_option(CLI::App& command, bool& keys_from_stdin, const std::string& keys) {
  command.add_flag("--keys", keys_from_stdin, "Read the operator keys (" + keys + ") from standard input even when it is no terminal (a pipe)");
}

}  // namespace curvestep::host
