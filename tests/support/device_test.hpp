#pragma once
// TEST() for a test whose body holds a KOKKOS_LAMBDA: nvcc refuses a device lambda inside a private
// member function, and GoogleTest's TestBody is private, so the body becomes a free function that
// TestBody calls. Assertions, GTEST_SKIP and failures behave as in TEST().
#include <gtest/gtest.h>

#define EULERFSI_DEVICE_TEST_BODY(suite, name) eulerfsi_device_test_##suite##_##name
#define DEVICE_TEST(suite, name)                            \
  void EULERFSI_DEVICE_TEST_BODY(suite, name)();            \
  TEST(suite, name) { EULERFSI_DEVICE_TEST_BODY(suite, name)(); } \
  void EULERFSI_DEVICE_TEST_BODY(suite, name)()
