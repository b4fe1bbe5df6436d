#include "support/png.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <stdexcept>

namespace fb::test {

std::vector<unsigned char> png(int width, int height, const std::vector<unsigned char>& rgba) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput writer(bytes);
  OIIO::Filesystem::IOProxy* proxy = &writer;
  auto out = OIIO::ImageOutput::create("png");
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  if (!out || !out->open("texture.png", spec) ||
      !out->write_image(OIIO::TypeDesc::UINT8, rgba.data()) || !out->close())
    throw std::runtime_error("cannot encode a test PNG: " + OIIO::geterror());
  return bytes;
}

}  // namespace fb::test
