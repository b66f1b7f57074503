// Reading a scene file (chapter 03), inside scene/ only: JSON parsed
// strictly (no key twice; a sphere list's numbers as one block), a reader
// whose every error names the file and the key, and the files a scene names.
#pragma once
#include "core/files.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace rg {

using nlohmann::json;

// nlohmann's own DOM builder, plus a check that no object has a key twice.
// (Its parser callback could do this too, but makes a 1e6-object file take
// minutes instead of seconds.) Keys are kept per open object, in a list
// reused across objects; a list that grows long moves into a set.
// An array under the key "data" (a sphere list's numbers, a million spheres'
// four million) does not become a million JSON values: its numbers go into
// one block of doubles, stored in the tree as a binary value, which JSON
// text cannot otherwise produce. An element that is not a number is NaN
// there (JSON has no NaN), for readSphereList to name.
class StrictJson : public nlohmann::detail::json_sax_dom_parser<json> {
public:
    explicit StrictJson(json& j) : json_sax_dom_parser(j, false) {}
    std::string duplicate;  // the first key found twice
    size_t errorPosition = 0;  // a syntax error: the characters read up to it
    std::string errorReason;

    template <class Exception>
    bool parse_error(std::size_t position, const std::string& token, const Exception& e) {
        errorPosition = position;
        // "[json.exception.parse_error.101] parse error at line 1, column 5: why"
        errorReason = e.what();
        size_t start = errorReason.find("] ");
        if (start != std::string::npos) errorReason.erase(0, start + 2);
        size_t colon = errorReason.find(": ");
        if (errorReason.rfind("parse error", 0) == 0 && colon != std::string::npos)
            errorReason.erase(0, colon + 2);
        return json_sax_dom_parser::parse_error(position, token, e);
    }

    bool start_object(std::size_t n) {
        // an element that is not a number
        if (capturing_) return inData(NAN), ++nested_, true;
        afterDataKey_ = false;
        if (++depth_ > levels_.size()) levels_.emplace_back();
        levels_[depth_ - 1].keys.clear();
        levels_[depth_ - 1].many.reset();
        return json_sax_dom_parser::start_object(n);
    }
    bool end_object() {
        if (capturing_) return --nested_, true;
        --depth_;
        return json_sax_dom_parser::end_object();
    }
    bool key(std::string& k) {
        if (capturing_) return true;
        Level& level = levels_[depth_ - 1];
        bool seen = level.many ? !level.many->insert(k).second
                               : std::find(level.keys.begin(), level.keys.end(), k) !=
                                     level.keys.end();
        if (!level.many) {
            level.keys.push_back(k);
            if (level.keys.size() > 32)
                level.many = std::make_unique<std::set<std::string>>(level.keys.begin(),
                                                                     level.keys.end());
        }
        if (seen && duplicate.empty()) duplicate = k;
        afterDataKey_ = k == "data";
        return json_sax_dom_parser::key(k);
    }
    bool start_array(std::size_t n) {
        if (capturing_) return inData(NAN), ++nested_, true;
        if (!std::exchange(afterDataKey_, false))
            return json_sax_dom_parser::start_array(n);
        capturing_ = true;
        bytes_.clear();
        return true;
    }
    bool end_array() {
        if (!capturing_) return json_sax_dom_parser::end_array();
        if (nested_ > 0) return --nested_, true;
        capturing_ = false;
        json::binary_t block(std::move(bytes_));  // moved into the tree, not copied
        bytes_ = {};
        return json_sax_dom_parser::binary(block);
    }
    bool number_integer(json::number_integer_t v) {
        return inData(double(v)) || json_sax_dom_parser::number_integer(v);
    }
    bool number_unsigned(json::number_unsigned_t v) {
        return inData(double(v)) || json_sax_dom_parser::number_unsigned(v);
    }
    bool number_float(double v, const std::string& text) {
        return inData(v) || json_sax_dom_parser::number_float(v, text);
    }
    bool string(std::string& v) { return inData(NAN) || json_sax_dom_parser::string(v); }
    bool boolean(bool v) { return inData(NAN) || json_sax_dom_parser::boolean(v); }
    bool null() { return inData(NAN) || json_sax_dom_parser::null(); }

private:
    // Inside a "data" array: records one element (what is inside a nested
    // container is not one) and returns true; elsewhere false.
    bool inData(double element) {
        afterDataKey_ = false;
        if (!capturing_) return false;
        if (nested_ == 0) {
            const auto* b = reinterpret_cast<const std::uint8_t*>(&element);
            bytes_.insert(bytes_.end(), b, b + sizeof element);
        }
        return true;
    }

    struct Level {
        std::vector<std::string> keys;
        std::unique_ptr<std::set<std::string>> many;
    };
    std::vector<Level> levels_;
    size_t depth_ = 0;
    bool afterDataKey_ = false, capturing_ = false;
    int nested_ = 0;  // containers open inside the captured array
    // the captured doubles, as the binary value holds them
    std::vector<std::uint8_t> bytes_;
};

// "line:column" (both from 1) of the character `position` counts up to.
inline std::string lineAndColumn(const std::string& text, size_t position) {
    size_t end = std::min(position > 0 ? position - 1 : 0, text.size());
    size_t line = 1 + size_t(std::count(text.begin(), text.begin() + long(end), '\n'));
    size_t lineStart = text.rfind('\n', end > 0 ? end - 1 : 0);
    size_t column =
        lineStart == std::string::npos || end == 0 ? end + 1 : end - lineStart;
    return std::to_string(line) + ":" + std::to_string(column);
}

// Reads one JSON value and names where it came from when it is wrong.
class Reader {
public:
    explicit Reader(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw InputError(file_ + ": " + key + ": " + what);
    }

    void onlyKeys(const json& j, const std::string& where,
                  const std::set<std::string>& allowed) const {
        if (!j.is_object()) fail(where, "must be an object");
        for (auto it = j.begin(); it != j.end(); ++it)
            if (!allowed.count(it.key())) {
                std::string list;
                for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
                fail(where.empty() ? it.key() : where + "." + it.key(),
                     "unknown key (known: " + list + ")");
            }
    }

    double number(const json& j, const std::string& key, double lo, double hi) const {
        if (!j.is_number()) fail(key, "must be a number");
        double v = j.get<double>();
        if (!std::isfinite(v) || v < lo || v > hi)
            fail(key,
                 "value " + j.dump() + " is outside [" + fmt(lo) + ", " + fmt(hi) + "]");
        return v;
    }

    glm::dvec3 vec3(const json& j, const std::string& key, double lo = -1e30,
                    double hi = 1e30) const {
        if (j.is_number()) {  // a single number means (v, v, v)
            double v = number(j, key, lo, hi);
            return {v, v, v};
        }
        if (!j.is_array() || j.size() != 3) fail(key, "must be an array of 3 numbers");
        return {number(j[0], key + "[0]", lo, hi), number(j[1], key + "[1]", lo, hi),
                number(j[2], key + "[2]", lo, hi)};
    }

    std::string string(const json& j, const std::string& key) const {
        if (!j.is_string()) fail(key, "must be a string");
        return j.get<std::string>();
    }

    bool boolean(const json& j, const std::string& key) const {
        if (!j.is_boolean()) fail(key, "must be true or false");
        return j.get<bool>();
    }

private:
    static std::string fmt(double v) {
        char b[32];
        std::snprintf(b, sizeof b, "%g", v);
        return b;
    }
    std::string file_;
};

// A file a scene names: relative to the scene file first, then to
// bin/assets/; it must be a regular file.
inline std::string findInput(const Reader& r, const std::string& scenePath,
                      const std::filesystem::path& name, const std::string& key) {
    std::filesystem::path besideScene =
        std::filesystem::path(scenePath).parent_path() / name;
    std::filesystem::path inAssets = executableDir() / "assets" / name;
    std::error_code error;  // a loop of links: no exception, the check below names it
    std::string found;
    if (std::filesystem::symlink_status(besideScene, error).type() !=
        std::filesystem::file_type::not_found)
        found = besideScene.string();
    else if (std::filesystem::symlink_status(inAssets, error).type() !=
             std::filesystem::file_type::not_found)
        found = inAssets.string();
    else
        r.fail(key, "no such file: " + name.string());
    requireRegularFile(found, scenePath + ": " + key);
    return found;
}

}  // namespace rg
