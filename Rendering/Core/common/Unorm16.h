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

// The first and last of `count` RGBA pixels (4 channels of 16 bits) that are not all zero;
// first > last when every pixel is zero (the drawn footprint of a converted image).
void FindNonZeroPixels(const std::uint16_t* rgba, int count, int& first, int& last);

}

#endif
