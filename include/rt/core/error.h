// Errors caused by bad input (scene files, PLY files, output paths).
// Every message is one line of the form "<file>: <place>: <what>", where <place>
// is a JSON pointer such as /Scene/Objects/Sphere/2/Center or "byte N" in a PLY.
#pragma once
#include <stdexcept>
#include <string>

namespace rt {

class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& msg) : std::runtime_error(msg) {}
};

// A command line that asks for something its input does not have (a pixel outside the
// image, a camera the scene lacks): the program reports it as a usage error (exit 2).
class UsageError : public std::runtime_error {
public:
    explicit UsageError(const std::string& msg) : std::runtime_error(msg) {}
};

}  // namespace rt
