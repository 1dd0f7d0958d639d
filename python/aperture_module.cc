// The `aperture` Python module (`make python`): camera models and calibration files, the gap
// detector, the LED tracker and aperture.run over a frame source, with NumPy arrays in and out.
// C++ exceptions arrive as Python exceptions: std::invalid_argument -> ValueError,
// std::runtime_error -> RuntimeError, with the C++ message (naming the input and the fix).
#include <pybind11/pybind11.h>

#include "python/bindings.h"

PYBIND11_MODULE(aperture, m) {
  m.doc() = "aperture: perception-centric quadrotor autonomy (C++17) from Python";
  m.attr("__version__") = APERTURE_VERSION;
  aperture::python::BindCameras(m);
  aperture::python::BindGapDetector(m);
  aperture::python::BindLedTracker(m);
  aperture::python::BindIo(m);
  aperture::python::BindRun(m);
}
