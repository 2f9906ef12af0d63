// Images between Lantern and NumPy: a render's image handed over without a
// copy, files read and written as the command line does, and the metrics of
// `lantern compare`.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>

#include "app/stats_report.h"
#include "film/image_metrics.h"
#include "python/bindings.h"

namespace lantern::python {

py::object to_array(Image&& image) {
  auto* owner = new Image(std::move(image));
  py::capsule free_image(owner, [](void* p) { delete static_cast<Image*>(p); });
  const py::ssize_t w = owner->width, h = owner->height, f = sizeof(float);
  return py::array_t<float>({h, w, py::ssize_t(3)}, {w * 3 * f, 3 * f, f}, owner->rgb.data(), free_image);
}

Image from_array(const py::handle& array) {
  auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a) throw py::type_error("expected an image: an array of real numbers of shape (height, width, 3)");
  if (a.ndim() != 3 || a.shape(2) != 3 || a.shape(0) < 1 || a.shape(1) < 1)
    throw py::value_error("expected an image of shape (height, width, 3); got an array of " +
                          std::to_string(a.ndim()) + " dimensions" +
                          (a.ndim() == 3 ? " with " + std::to_string(a.shape(2)) + " channels" : std::string()));
  Image im;
  im.height = int(a.shape(0));
  im.width = int(a.shape(1));
  im.rgb.assign(a.data(), a.data() + a.size());
  return im;
}

py::object from_json_text(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

namespace {

// The metrics `lantern compare` prints.
py::object compare(const py::handle& image, const py::handle& reference) {
  const Image a = from_array(image), r = from_array(reference);
  if (a.width != r.width || a.height != r.height)
    throw py::value_error("the images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                          " against " + std::to_string(r.width) + "x" + std::to_string(r.height));
  ImageComparison m;
  {
    py::gil_scoped_release release;
    m = compare_images(a, r);
  }
  return from_json_text(comparison_json(m).dump());  // the command line's names and values
}

void write(const std::string& path, const py::handle& array, const ImageMetadata& metadata) {
  Image im = from_array(array);
  if (!can_write_image_format(path))
    throw py::value_error(path + ": no image format Lantern writes has this extension (.exr, .pfm, .hdr, .png, ...)");
  py::gil_scoped_release release;
  write_image(path, im, metadata);
}

}  // namespace

void bind_images(py::module_& m) {
  m.def(
      "read_image",
      [](const std::string& path) {
        Image im;
        {
          py::gil_scoped_release release;
          im = read_image(path);
        }
        return to_array(std::move(im));
      },
      py::arg("path"),
      "An image file as a (height, width, 3) float32 array of linear values (8-bit files decoded as textures "
      "are: docs/textures.md).");
  m.def("write_image", &write, py::arg("path"), py::arg("image"), py::arg("metadata") = ImageMetadata{},
        "Write a (height, width, 3) array; the extension picks the format (.exr and .pfm keep floats, .png is "
        "sRGB-encoded); metadata: (key, value) string pairs for the header. Written to a temporary file and "
        "renamed, so a failure leaves no truncated image.");
  m.def("image_metadata", &read_image_metadata, py::arg("path"), py::arg("prefix") = "lantern:",
        "The string attributes of an image's header whose names start with prefix, as (key, value) pairs.");
  m.def("compare", &compare, py::arg("image"), py::arg("reference"),
        "Error of an image against a reference, as `lantern compare` measures it: mse, relmse (Rousselle et al. "
        "2011, eps 0.01), relmse_robust (without the worst 0.01% of pixels), mae, psnr, pbrt-v4's per-channel "
        "pbrt_mse and pbrt_mrse, per-channel means and their ratio, and the pixels that are not finite.");
  m.def(
      "relative_error_image",
      [](const py::handle& image, const py::handle& reference, double scale, bool legend) {
        return to_array(relative_error_image(from_array(image), from_array(reference), scale, legend));
      },
      py::arg("image"), py::arg("reference"), py::arg("scale") = 1.0, py::arg("legend") = false,
      "A false-colour map of the per-pixel relative squared error (blue 0, red at or above scale); with legend, "
      "a bar of the scale below it.");
}

}  // namespace lantern::python
