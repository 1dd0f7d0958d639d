# Every package here comes from Debian 12 (scripts/install-deps.sh installs them).
# The libraries' own dependencies (installed with apertureConfig.cmake):
include(ApertureLibraryDependencies)
# The command line, the tests and the micro-benchmarks:
find_package(CLI11 REQUIRED)
find_package(GTest REQUIRED)
find_package(benchmark REQUIRED)
# The Python module (python/): Debian's pybind11 on the system Python 3.
# Debian's interpreter (/usr), whose numpy and pytest scripts/install-deps.sh installs: a
# user-level Python first on PATH (pyenv, conda) has neither. -DPython3_ROOT_DIR=... overrides.
if(NOT DEFINED Python3_ROOT_DIR)
  set(Python3_ROOT_DIR /usr)
endif()
find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)
find_package(pybind11 REQUIRED CONFIG)
