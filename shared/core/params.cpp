#include "core/params.h"

#include <CLI/CLI.hpp>

#include <map>

namespace rg {

namespace {
// "--no-accumulate" -> "accumulate", "--fixed-epsilon" -> "fixed epsilon"
std::string labelOf(const std::string& flag, bool inverted) {
    std::string name = flag.substr(flag.find_first_not_of('-'));
    if (inverted && name.rfind("no-", 0) == 0) name = name.substr(3);
    for (char& c : name)
        if (c == '-') c = ' ';
    return name;
}
}  // namespace

Param& Params::add(Param p) {
    p.label = labelOf(p.flag, p.inverted);
    params_.push_back(std::move(p));
    return params_.back();
}

Param& Params::integer(const std::string& flag, int& value, const std::string& help,
                       int min, int max) {
    return add({.kind = Param::Kind::Integer,
                .flag = flag,
                .help = help,
                .integer = &value,
                .min = double(min),
                .max = double(max)});
}

Param& Params::number(const std::string& flag, float& value, const std::string& help,
                      double min, double max) {
    return add({.kind = Param::Kind::Number,
                .flag = flag,
                .help = help,
                .number = &value,
                .min = min,
                .max = max});
}

Param& Params::choice(const std::string& flag, int& value, const std::string& help,
                      std::vector<std::string> choices) {
    return add({.kind = Param::Kind::Choice,
                .flag = flag,
                .help = help,
                .integer = &value,
                .choices = std::move(choices)});
}

Param& Params::toggle(const std::string& flag, bool& value, const std::string& help,
                      bool inverted) {
    return add({.kind = Param::Kind::Toggle,
                .flag = flag,
                .help = help,
                .toggle = &value,
                .inverted = inverted});
}

Param& Params::text(const std::string& flag, std::string& value,
                    const std::string& help) {
    return add({.kind = Param::Kind::Text,
                .flag = flag,
                .help = help,
                .text = &value,
                .live = false});
}

void Params::addTo(CLI::App& app) const {
    for (const Param& p : params_) {
        CLI::Option* option = nullptr;
        switch (p.kind) {
        case Param::Kind::Integer:
            option = app.add_option(p.flag, *p.integer, p.help)
                         ->check(CLI::Range(int(p.min), int(p.max)));
            break;
        case Param::Kind::Number:
            option = app.add_option(p.flag, *p.number, p.help);
            if (!p.check) option->check(CLI::Range(p.min, p.max));
            break;
        case Param::Kind::Choice: {
            std::map<std::string, int> names;
            for (size_t i = 0; i < p.choices.size(); ++i) names[p.choices[i]] = int(i);
            std::string words;
            for (const std::string& c : p.choices)
                words += (words.empty() ? "" : "|") + c;
            option = app.add_option(p.flag, *p.integer, p.help)
                         ->transform(CLI::CheckedTransformer(names, CLI::ignore_case))
                         // --help names the words, not the numbers behind them
                         ->option_text(words);
            break;
        }
        case Param::Kind::Toggle:
            // --no-x sets x to false (a callback: --help shows no "{false}")
            if (p.inverted)
                option = app.add_flag_callback(
                    p.flag, [toggle = p.toggle] { *toggle = false; }, p.help);
            else
                option = app.add_flag(p.flag, *p.toggle, p.help);
            break;
        case Param::Kind::Text:
            option = app.add_option(p.flag, *p.text, p.help);
            break;
        }
        if (p.check) option->check(p.check);
        if (p.kind == Param::Kind::Choice)
            option->description(p.help + " (default: " + p.choices[size_t(*p.integer)] +
                                ")");
        else if (p.kind != Param::Kind::Toggle && p.kind != Param::Kind::Text)
            option->capture_default_str();
    }
}

nlohmann::json Params::values() const {
    nlohmann::json out = nlohmann::json::object();
    for (const Param& p : params_) {
        nlohmann::json& value = out[p.flag.substr(2)];
        switch (p.kind) {
        case Param::Kind::Integer: value = *p.integer; break;
        case Param::Kind::Number: value = *p.number; break;
        case Param::Kind::Choice: value = p.choices[size_t(*p.integer)]; break;
        case Param::Kind::Toggle: value = *p.toggle != p.inverted; break;
        case Param::Kind::Text: value = *p.text; break;
        }
    }
    return out;
}

}  // namespace rg
