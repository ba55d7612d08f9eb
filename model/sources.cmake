# model/'s sources, listed once: the library here and the fuzz targets (tests/fuzz), which build
# them with their own flags, read this list.
set(MAPTR_MODEL_SOURCES params.cpp motor.cpp battery.cpp kinematics.cpp dynamics.cpp reach.cpp motor_fault.cpp)
