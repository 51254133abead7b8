// src/image_oiio.cpp -- the C interface of image.h over OpenImageIO. No exception or OIIO type crosses it.
extern "C" {
#include "error.h"
}
#include "image.h"
#include <OpenImageIO/imageio.h>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unistd.h>

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

// "dir/name.ext" -> "dir/.name.tmp-PID.ext": same directory (so rename is atomic), same extension (so the
// format plugin is the same), hidden, and distinct between concurrent processes.
static std::string temporary_name(const std::string &path) {
    size_t slash = path.find_last_of('/');
    size_t base = slash == std::string::npos ? 0 : slash + 1;
    size_t dot = path.find_last_of('.');
    std::string ext = dot != std::string::npos && dot > base ? path.substr(dot) : "";
    std::string stem = path.substr(base, path.size() - base - ext.size());
    return path.substr(0, base) + "." + stem + ".tmp-" + std::to_string(static_cast<long>(getpid())) + ext;
}

// Writes pixels of type `in` to `path` as `stored`, through a temporary file renamed over `path` once complete.
static iacsg_status write_image(const char *path, int width, int height, int channels, TypeDesc in,
                                const void *pixels, TypeDesc stored, iacsg_error *err) {
    try {
        auto out = ImageOutput::create(path);
        if (!out)
            return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: no image format for this file name (%s)", path,
                                   OIIO::geterror().c_str());
        ImageSpec spec(width, height, channels, stored);
        /* PNG: no row filter, zlib level 4. libpng's default tries its five filters on every row and keeps the
         * best guess, most of a frame's encoding time. 1024x1024, adaptive filters at level 1 (before) against
         * none at level 4: reference view 39 -> 13 ms, 249 -> 160 KB; tangle | sphere 53 -> 25 ms, 207 -> 173 KB;
         * decocube | heart 53 -> 27 ms, 254 -> 248 KB; 1024 spheres 98 -> 91 ms, 1053 -> 1067 KB. Unfiltered at
         * level 1 was faster still but 12-20 % larger. Other formats ignore both attributes. */
        spec.attribute("png:compressionLevel", 4);
        spec.attribute("png:filter", 0x08); /* PNG_FILTER_NONE */
        std::string tmp = temporary_name(path);
        bool ok = out->open(tmp, spec) && out->write_image(in, pixels) && out->close();
        if (!ok) {
            std::string msg = out->geterror();
            out.reset();
            std::remove(tmp.c_str());
            return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: cannot write: %s", path, msg.c_str());
        }
        out.reset();
        if (std::rename(tmp.c_str(), path) != 0) {
            int e = errno;
            std::remove(tmp.c_str());
            return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: cannot rename the finished image: %s", path,
                                   std::strerror(e));
        }
        return IACSG_OK;
    } catch (const std::exception &e) {
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: %s", path, e.what());
    }
}

extern "C" iacsg_status iacsg_image_write(const char *path, int width, int height, int channels,
                                          const float *pixels, int as_float, iacsg_error *err) {
    return write_image(path, width, height, channels, TypeDesc::FLOAT, pixels,
                       as_float ? TypeDesc::FLOAT : TypeDesc::UINT8, err);
}

extern "C" iacsg_status iacsg_image_write_bytes(const char *path, int width, int height, int channels,
                                                const unsigned char *pixels, iacsg_error *err) {
    return write_image(path, width, height, channels, TypeDesc::UINT8, pixels, TypeDesc::UINT8, err);
}

extern "C" iacsg_status iacsg_image_check_format(const char *path, iacsg_error *err) {
    try {
        if (!ImageOutput::create(path))
            return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: no image format for this file name (%s)", path,
                                   OIIO::geterror().c_str());
        return IACSG_OK;
    } catch (const std::exception &e) {
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: %s", path, e.what());
    }
}

extern "C" iacsg_status iacsg_image_read(const char *path, int *width, int *height, int *channels, float **pixels,
                                         iacsg_error *err) {
    *pixels = nullptr;
    try {
        auto in = ImageInput::open(path);
        if (!in)
            return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: cannot read: %s", path, OIIO::geterror().c_str());
        const ImageSpec &spec = in->spec();
        size_t count = static_cast<size_t>(spec.width) * spec.height * spec.nchannels;
        float *data = static_cast<float *>(std::malloc(count * sizeof(float)));
        if (!data)
            return iacsg_error_set(err, IACSG_ERR_NOMEM, 0, 0, "%s: out of memory", path);
        if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, data)) {
            std::free(data);
            return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: cannot read: %s", path, in->geterror().c_str());
        }
        *width = spec.width;
        *height = spec.height;
        *channels = spec.nchannels;
        *pixels = data;
        return IACSG_OK;
    } catch (const std::exception &e) {
        return iacsg_error_set(err, IACSG_ERR_IO, 0, 0, "%s: %s", path, e.what());
    }
}
