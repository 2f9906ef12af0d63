// The image module's entry point: the table of its functions.
#include "imageio/oiio_module.h"

extern "C" __attribute__((visibility("default"))) const lantern::ImageIoModule* lantern_image_io_module() {
  using namespace lantern::oiio;
  static const lantern::ImageIoModule table{lantern::kImageIoModuleVersion,
                                            write_image,
                                            can_write_format,
                                            read_image,
                                            read_image_metadata,
                                            load_texture_image,
                                            image_resolution,
                                            prepare_texture,
                                            cache_create,
                                            cache_destroy,
                                            cache_add,
                                            cache_texture,
                                            cache_stats,
                                            cache_reset_lookup_stats};
  return &table;
}
