// The doctest entry point of the whole suite (one executable, one CTest test per TEST_CASE).
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
