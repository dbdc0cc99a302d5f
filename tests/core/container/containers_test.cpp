// SPDX-License-Identifier: MIT
// InlineVector and RingBuffer, which share their element count (detail::FixedCapacity): counts,
// full means full, order of elements, and clearing. Expected values are the pushed values themselves.
#include <cstddef>

#include <catch2/catch.hpp>

#include <curvestep/core/container/inline_vector.hpp>
#include <curvestep/core/container/ring_buffer.hpp>

using namespace curvestep;

TEST_CASE("containers: an inline vector keeps pushed elements in order until full", "[core][container]") {
  InlineVector<int, 3> v;
  STATIC_REQUIRE(InlineVector<int, 3>::capacity() == 3);
  CHECK(v.empty());
  CHECK(v.size() == 0);
  CHECK(v.available() == 3);
  CHECK(v.begin() == v.end());
  CHECK(v.try_push(10));
  CHECK(v.try_push(20));
  CHECK_FALSE(v.empty());
  CHECK_FALSE(v.full());
  CHECK(v.available() == 1);
  CHECK(v.try_push(30));
  CHECK(v.full());
  CHECK(v.available() == 0);
  CHECK_FALSE(v.try_push(40));  // full: nothing stored
  REQUIRE(v.size() == 3);
  CHECK(v[0] == 10);
  CHECK(v[1] == 20);
  CHECK(v[2] == 30);
  int sum = 0;
  for (const int x : v) sum += x;
  CHECK(sum == 60);
  v.clear();
  CHECK(v.empty());
  CHECK(v.try_push(7));
  CHECK(v[0] == 7);
}

TEST_CASE("containers: a ring buffer is first in first out across the wrap", "[core][container]") {
  RingBuffer<int, 3> r;
  STATIC_REQUIRE(RingBuffer<int, 3>::capacity() == 3);
  CHECK(r.empty());
  CHECK(r.try_push(1));
  CHECK(r.try_push(2));
  CHECK(r.try_push(3));
  CHECK(r.full());
  CHECK_FALSE(r.try_push(4));
  CHECK(r.front() == 1);
  r.pop_front();
  CHECK(r.available() == 1);
  CHECK(r.try_push(4));  // stored in the slot the 1 left: the wrap
  REQUIRE(r.size() == 3);
  CHECK(r[0] == 2);
  CHECK(r[1] == 3);
  CHECK(r[2] == 4);
  r.pop_front();
  r.pop_front();
  CHECK(r.front() == 4);
  CHECK(r.size() == 1);
  r.clear();
  CHECK(r.empty());
  CHECK(r.available() == 3);
}
