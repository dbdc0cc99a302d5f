// SPDX-License-Identifier: MIT
// Umbrella header of curvestep::protocol: CRC, COBS, frames, messages and both link ends.
#pragma once

#include <curvestep/protocol/byte_io.hpp>
#include <curvestep/protocol/cobs.hpp>
#include <curvestep/protocol/crc16.hpp>
#include <curvestep/protocol/crc32.hpp>
#include <curvestep/protocol/frame.hpp>
#include <curvestep/protocol/frame_decoder.hpp>
#include <curvestep/protocol/limits.hpp>
#include <curvestep/protocol/link_receiver.hpp>
#include <curvestep/protocol/link_sender.hpp>
#include <curvestep/protocol/messages.hpp>
#include <curvestep/protocol/segment_curves.hpp>
