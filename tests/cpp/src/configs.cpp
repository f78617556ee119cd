// Every config of asset.hpp encoded (XCDR1 LE): "topic hex" lines, compared by the test
// with rapidgen's reference encoder on the descriptor's computed configs.
#include <iostream>
#include <rapid_k10red/asset.hpp>

#include "common.hpp"

template <class T>
void show(const char* topic, const T& value) {
    std::cout << topic << " ";
    for (auto b : rapidgen::cdr::serialize(value)) std::cout << "0123456789abcdef"[b >> 4] << "0123456789abcdef"[b & 15];
    std::cout << "\n";
}

int main() {
    std::cout << rapid_k10red::PUBLICATIONS.size() << " publications\n";
#define RAPIDGEN_CONFIG(FN, TOPIC) show(TOPIC, rapid_k10red::FN());
#include "configs.inc"
#undef RAPIDGEN_CONFIG
}
