// aperture.read_image: image files as frame sources read them (perception/io), for users without
// python3-opencv.
#include "perception/io/image_file_reader.h"
#include "python/bindings.h"
#include "python/numpy_image.h"

namespace aperture::python {
namespace py = pybind11;

void BindIo(py::module_& m) {
  m.def(
      "read_image",
      [](const std::string& path, bool color) {
        return ToNumpy(perception::ReadImageFile(
            path, color ? perception::ColorMode::kColor : perception::ColorMode::kGray));
      },
      py::arg("path"), py::arg("color") = false,
      "Reads an image file as uint8 (H, W) gray or (H, W, 3) BGR; raises RuntimeError naming an "
      "unreadable, corrupt or truncated file.");
}

}  // namespace aperture::python
