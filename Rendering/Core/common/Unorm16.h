// Unorm16: float colours to 16-bit normalised channels, as the CPU mappers' images are shown
// (a quarter of a float upload, in 1/65535 steps, far below the 8-bit framebuffer's).
#ifndef accelvolume_Unorm16_h
#define accelvolume_Unorm16_h

#include <cstddef>
#include <cstdint>

namespace accelvolume
{

// out[i] = v * 65535 + 0.5 truncated, v = in[i] clamped to [0, 1] (NaN as 0); the same values
// on every CPU (16 at a time where it has AVX-512, else 8 with SSE2).
void ConvertToUnorm16(const float* in, std::size_t count, std::uint16_t* out);

// Rows [v0, v1) of an RGBA float image `width` pixels wide into rows of width + 1 16-bit pixels
// (the last one zero: a bilinear lookup past the image reads zero), row v at
// padded + 4 (width + 1) v, with each row's first and last pixel that is not all zero in
// rowFirst[v], rowLast[v] (first > last: none; the drawn footprint of a warped image).
void ConvertRowsPadded(const float* image, int width, int v0, int v1, std::uint16_t* padded,
  int* rowFirst, int* rowLast);

}

#endif
