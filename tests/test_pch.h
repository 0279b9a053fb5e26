// The test programs' precompiled header: the large library headers every test file
// would otherwise parse again (GoogleTest, nlohmann/json) and the standard headers most
// of them use. The Makefile compiles it once per build folder and precision and passes
// it to each test file with -include; a test file still includes what it uses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>
