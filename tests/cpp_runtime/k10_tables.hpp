// K10Red's tables for the logic suite: the generated ones (bridge/tables.cpp of
// `rapidgen generate specs/assets/k10.yaml --lang cpp`), nothing written by hand.
#ifndef K10_TABLES_HPP
#define K10_TABLES_HPP

#include <rapid_runtime/tables.hpp>

#include "handlers.hpp"  // the generated bridge/handlers.hpp: rapid_k10red::bridge::tables()

inline const rapid_runtime::Tables& k10_tables() { return rapid_k10red::bridge::tables(); }

#endif
