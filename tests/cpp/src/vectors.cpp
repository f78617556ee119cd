// Every golden vector (stdin: "id type le_hex be_hex" lines) decoded from both byte
// orders and re-encoded in both, byte-identical; prints "ok N" or the failures.
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "common.hpp"

template <class T>
std::string check(const Bytes& le, const Bytes& be) {
    T a = rapidgen::cdr::deserialize<T>(le);
    T b = rapidgen::cdr::deserialize<T>(be);
    if (!(a == b)) return "LE and BE decode to different values";
    if (rapidgen::cdr::serialize(a, rapidgen::cdr::Endianness::little) != le) return "LE re-encode differs";
    if (rapidgen::cdr::serialize(b, rapidgen::cdr::Endianness::big) != be) return "BE re-encode differs";
    if (rapidgen::cdr::serialize(a, rapidgen::cdr::Endianness::big) != be) return "LE value encoded BE differs";
    return "";
}

int main() {
    std::map<std::string, std::string (*)(const Bytes&, const Bytes&)> table;
#define RAPIDGEN_TYPE(T, NAME) table[NAME] = &check<T>;
#include "dispatch.inc"
#undef RAPIDGEN_TYPE
    std::string id, type, le, be;
    int ok = 0, bad = 0;
    while (std::cin >> id >> type >> le >> be) {
        std::string why;
        auto it = table.find(type);
        try {
            why = it == table.end() ? "no such type" : it->second(unhex(le), unhex(be));
        } catch (const std::exception& e) {
            why = std::string("exception: ") + e.what();
        }
        if (why.empty()) {
            ++ok;
        } else {
            ++bad;
            std::cout << "FAIL " << id << ": " << why << "\n";
        }
    }
    std::cout << "ok " << ok << "\n";
    return bad == 0 ? 0 : 1;
}
