// Helpers shared by the test programs.
#pragma once
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <rapid_k10red/types.hpp>

using Bytes = std::vector<std::uint8_t>;

inline Bytes unhex(const std::string& s) {
    if (s.size() % 2 != 0) throw std::invalid_argument("odd hex");
    Bytes out(s.size() / 2);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<std::uint8_t>(std::stoi(s.substr(2 * i, 2), nullptr, 16));
    return out;
}
