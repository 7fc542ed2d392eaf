// The Catch2 main of the test suite (kept alone in its translation unit: it compiles once).
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>
