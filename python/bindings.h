#pragma once
// The parts of the `aperture` Python module (aperture_module.cc puts them together). Poses cross
// as 4x4 homogeneous matrices (numpy float64), named like the C++ fields (T_CG maps G into C).
#include <pybind11/pybind11.h>

namespace aperture::python {

void BindCameras(pybind11::module_& m);      // camera models, calibration files
void BindGapDetector(pybind11::module_& m);  // perception/gap
void BindLedTracker(pybind11::module_& m);   // perception/led
void BindIo(pybind11::module_& m);           // aperture.read_image
void BindRun(pybind11::module_& m);          // aperture.run over a frame source

}  // namespace aperture::python
