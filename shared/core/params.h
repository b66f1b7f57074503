// A chapter's parameters, declared once. Each one becomes a command-line
// option (CLI11) and, in a window, a control in the overlay (viewer.h), so
// the two can never disagree on a name, a range or a default.
#pragma once
#include "core/cli.h"  // CLI::App, declared ahead

#include <nlohmann/json.hpp>

#include <deque>
#include <functional>
#include <string>
#include <vector>

namespace rg {

struct Param {
    enum class Kind { Integer, Number, Choice, Toggle, Text };
    Kind kind = Kind::Integer;
    std::string flag;   // "--depth"
    std::string label;  // the overlay's name for it: "depth"
    std::string help;
    int* integer = nullptr;    // Integer and Choice (the index into choices)
    float* number = nullptr;   // Number
    bool* toggle = nullptr;    // Toggle
    std::string* text = nullptr;  // Text: a path (chapter 14's --photons-ply)
    double min = 0, max = 0;   // Integer and Number
    bool logarithmic = false;  // Number: a log slider (0 still allowed: "off")
    bool inverted = false;     // Toggle: the flag clears the value (--no-accumulate)
    std::vector<std::string> choices;
    bool live = true;          // false: read once at start (the overlay shows it greyed)
    // the overlay's section: "" Parameters, "view" View (the camera, exposure, lights)
    std::string section;
    // Checks a command-line value; returns "" or the reason it is refused.
    std::function<std::string(const std::string&)> check;
};

class Params {
public:
    // The returned Param stays valid (a deque never moves its elements), so
    // a chapter can refine it: params.number(...).check = ...;
    Param& integer(const std::string& flag, int& value, const std::string& help, int min,
                   int max);
    Param& number(const std::string& flag, float& value, const std::string& help,
                  double min, double max);
    Param& choice(const std::string& flag, int& value, const std::string& help,
                  std::vector<std::string> choices);
    Param& toggle(const std::string& flag, bool& value, const std::string& help,
                  bool inverted = false);
    // A file to write (read at start only: the overlay shows it greyed).
    Param& text(const std::string& flag, std::string& value, const std::string& help);

    // Adds every parameter to the command line, with its default shown.
    void addTo(CLI::App& app) const;
    // The values now, by flag without its dashes ({"depth": 6, ...}): every
    // report says what made its picture, headless or a window's F2.
    nlohmann::json values() const;
    const std::deque<Param>& all() const { return params_; }

private:
    Param& add(Param p);
    std::deque<Param> params_;
};

}  // namespace rg
