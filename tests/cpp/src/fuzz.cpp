// Bounded property test of the decoders, built with AddressSanitizer and UBSan.
// stdin: the golden vectors ("id type le_hex be_hex"), used as seeds; argv[1]: mutations
// per vector. Every truncation, random mutation and random buffer must either decode (and
// then re-encode to a value that decodes equal) or raise rapidgen::cdr::DecodeError:
// any other exception fails, a memory error aborts.
#include <iostream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "common.hpp"

static long decoded = 0, refused = 0;

template <class T>
void one(const Bytes& bytes) {
    T v;
    try {
        rapidgen::cdr::deserialize(bytes.data(), bytes.size(), v);
    } catch (const rapidgen::cdr::DecodeError&) {
        ++refused;
        return;
    }
    ++decoded;
    Bytes again = rapidgen::cdr::serialize(v);
    T w = rapidgen::cdr::deserialize<T>(again);
    if (!(w == v) && rapidgen::cdr::serialize(w) != again) throw std::logic_error("re-encoded value decodes differently");
}

template <class T>
void run(const Bytes& seed, int mutations, std::mt19937& rng) {
    for (std::size_t n = 0; n <= seed.size(); ++n) one<T>(Bytes(seed.begin(), seed.begin() + static_cast<long>(n)));
    std::uniform_int_distribution<int> byte(0, 255);
    for (int i = 0; i < mutations; ++i) {
        Bytes m = seed;
        int edits = 1 + static_cast<int>(rng() % 4);
        for (int e = 0; e < edits && m.size() > 4; ++e) {
            std::size_t at = 4 + rng() % (m.size() - 4);
            switch (rng() % 4) {
            case 0: m[at] = static_cast<std::uint8_t>(byte(rng)); break;
            case 1: m[at] ^= static_cast<std::uint8_t>(1u << (rng() % 8)); break;
            case 2:  // a huge or boundary count at an aligned offset
                at &= ~std::size_t{3};
                if (at + 4 <= m.size() && at >= 4) {
                    static const std::uint32_t counts[] = {0, 1, 0x7fffffffu, 0xffffffffu, 0x10000u, 17u, 65u, 2049u};
                    std::uint32_t c = counts[rng() % 8];
                    std::memcpy(&m[at], &c, 4);
                }
                break;
            default: m.resize(4 + rng() % (m.size() - 3)); break;
            }
        }
        one<T>(m);
    }
    for (int i = 0; i < mutations / 4; ++i) {
        Bytes r(rng() % 256);
        for (auto& b : r) b = static_cast<std::uint8_t>(byte(rng));
        if (r.size() >= 2) { r[0] = 0; r[1] = static_cast<std::uint8_t>(rng() % 2); }
        one<T>(r);
    }
}

int main(int argc, char** argv) {
    int mutations = argc > 1 ? std::atoi(argv[1]) : 200;
    std::map<std::string, void (*)(const Bytes&, int, std::mt19937&)> table;
#define RAPIDGEN_TYPE(T, NAME) table[NAME] = &run<T>;
#include "dispatch.inc"
#undef RAPIDGEN_TYPE
    std::mt19937 rng(12345);
    std::string id, type, le, be;
    int seeds = 0;
    try {
        while (std::cin >> id >> type >> le >> be) {
            auto it = table.find(type);
            if (it == table.end()) continue;
            it->second(unhex(le), mutations, rng);
            it->second(unhex(be), mutations, rng);
            seeds += 2;
        }
    } catch (const std::exception& e) {
        std::cout << "FAIL " << id << ": " << e.what() << "\n";
        return 1;
    }
    std::cout << "seeds " << seeds << " decoded " << decoded << " refused " << refused << "\n";
    return 0;
}
