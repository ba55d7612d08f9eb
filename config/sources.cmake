# The scenario's sources, listed once: the library here and the fuzz targets (tests/fuzz), which
# build them with their own flags, read this list. settings.cpp (the fixed settings' table, which
# needs the Level-2 solver's) is the library's alone.
set(MAPTR_SCENARIO_SOURCES scenario.cpp scenario_checks.cpp fields.cpp scenario_fields.cpp waypoints.cpp faults.cpp hosts_section.cpp)
