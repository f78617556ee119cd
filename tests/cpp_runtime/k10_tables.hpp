// K10Red's tables, written by hand from generated/k10/python/rapid_k10red/asset_tables.py:
// the declarative data phase 2 of issue 21 will generate (rapid_runtime::Tables).
#ifndef K10_TABLES_HPP
#define K10_TABLES_HPP

#include <rapid_runtime/tables.hpp>

const rapid_runtime::Tables& k10_tables();

#endif
