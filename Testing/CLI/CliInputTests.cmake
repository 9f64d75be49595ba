# Bad-input tests of the accelvolume CLI: each malformed or absurd input must end with exactly one
# "accelvolume: error: ..." line and exit code 1 (2 for bad flag values), with no crash, no hang
# and no huge allocation. Included from Testing/CLI/CMakeLists.txt (needs accelvolume_cli_test).
# The inputs are written at test time by MakeBadInputs (one fixture test; no binaries are
# committed). Every run is capped at 2 GiB of address space with prlimit, so a loader that tried to
# allocate the gigabytes a header merely claims would fail with a different message. Labels: cli,
# badinput. docs/robustness-cli.md lists every case with the message the CLI prints.
add_executable(accelvolume_make_bad_inputs
  "${CMAKE_SOURCE_DIR}/Testing/Data/BadInputs/MakeBadInputs.cxx")
target_link_libraries(accelvolume_make_bad_inputs PRIVATE ZLIB::ZLIB)
set(_av_bad "${CMAKE_CURRENT_BINARY_DIR}/cli-bad-inputs")
add_test(NAME accelvolume.cli.badinput_setup COMMAND accelvolume_make_bad_inputs "${_av_bad}")
set_tests_properties(accelvolume.cli.badinput_setup PROPERTIES
  FIXTURES_SETUP AccelVolumeBadInputs LABELS "cli;badinput" TIMEOUT 60)

find_program(ACCELVOLUME_PRLIMIT_EXECUTABLE prlimit
  DOC "util-linux prlimit: caps the address space of the CLI bad-input tests")
mark_as_advanced(ACCELVOLUME_PRLIMIT_EXECUTABLE)
set(_av_bad_launcher "")
if (ACCELVOLUME_PRLIMIT_EXECUTABLE)
  set(_av_bad_launcher "LAUNCHER=${ACCELVOLUME_PRLIMIT_EXECUTABLE}|--as=2147483648")
else ()
  message(STATUS "AccelVolume: no 'prlimit'; the CLI bad-input tests run without a memory cap")
endif ()

# accelvolume_bad_input(NAME FILE REGEX [EXPECT code] [ARGS flags...]): renders FILE (under the
# generated folder) and expects one error line matching REGEX and exit code EXPECT (default 1).
function(accelvolume_bad_input name file regex)
  cmake_parse_arguments(PARSE_ARGV 3 bad "" "EXPECT" "ARGS")
  if (NOT DEFINED bad_EXPECT)
    set(bad_EXPECT 1)
  endif ()
  accelvolume_cli_test(badinput_${name} EXPECT ${bad_EXPECT}
    ARGS render --input "${_av_bad}/${file}" --size 32 32 --quiet ${bad_ARGS}
    VARS "ERROR_REGEX=${regex}" ${_av_bad_launcher})
  set_tests_properties(accelvolume.cli.badinput_${name} PROPERTIES
    LABELS "cli;badinput" FIXTURES_REQUIRED AccelVolumeBadInputs TIMEOUT 60)
endfunction()

# Headerless raw: truncated files, --dims that do not match the file, absurd and overflowing
# --dims (refused before any allocation), zero or negative --dims and unknown --type (usage, 2).
accelvolume_bad_input(raw_truncated truncated_4x4x4_uint8.raw
  "size mismatch: .* has 40 bytes but 4x4x4 uint8 needs 64 bytes")
accelvolume_bad_input(raw_dims_too_small plain.raw "has 64 bytes but 4x4x3 uint8 needs 48 bytes"
  ARGS --dims 4 4 3 --type uint8)
accelvolume_bad_input(raw_dims_too_large plain.raw "has 64 bytes but 4x4x5 uint8 needs 80 bytes"
  ARGS --dims 4 4 5 --type uint8)
accelvolume_bad_input(raw_dims_absurd plain.raw
  "refusing 100000x100000x100000: more than 2.31 voxels"
  ARGS --dims 100000 100000 100000 --type float64)
accelvolume_bad_input(raw_dims_overflow plain.raw "refusing 3000000x3000000x3000000: more than 2.31"
  ARGS --dims 3000000 3000000 3000000 --type uint8)
accelvolume_bad_input(raw_name_absurd huge_100000x100000x100000_uint8.raw "more than 2.31 voxels")
accelvolume_bad_input(raw_dims_zero plain.raw "--dims values must be at least 1, got 0 4 4"
  EXPECT 2 ARGS --dims 0 4 4 --type uint8)
accelvolume_bad_input(raw_dims_negative plain.raw "--dims values must be at least 1, got -4 4 4"
  EXPECT 2 ARGS --dims -4 4 4 --type uint8)
accelvolume_bad_input(raw_dims_beyond_int plain.raw "--dims expects an integer, got '4000000000'"
  EXPECT 2 ARGS --dims 4000000000 1 1 --type uint8)
accelvolume_bad_input(raw_type_unknown plain.raw "invalid value 'uint64' for --type"
  EXPECT 2 ARGS --dims 4 4 4 --type uint64)
accelvolume_bad_input(raw_type_missing plain.raw "needs --type" ARGS --dims 4 4 4)
accelvolume_bad_input(raw_no_layout plain.raw "needs --dims and --type")

# gzip-compressed raw: truncated, too short or long, bad magic, CRC error, garbage after the
# gzip header, trailing bytes after the stream, and a 38-byte file claiming 16 GiB.
accelvolume_bad_input(gz_truncated truncated_4x4x4_uint8.raw.gz
  "truncated gzip data .* the stream ends after 60 of 64 bytes")
accelvolume_bad_input(gz_short short_4x4x4_uint8.raw.gz "decompresses to 40 bytes but 4x4x4")
accelvolume_bad_input(gz_long long_4x4x4_uint8.raw.gz "decompresses to more than 64 bytes")
accelvolume_bad_input(gz_dims_mismatch good_4x4x4_uint8.raw.gz
  "decompresses to 64 bytes but 4x4x8 uint8 needs 128 bytes" ARGS --dims 4 4 8)
accelvolume_bad_input(gz_bad_magic notgzip_4x4x4_uint8.raw.gz "is not gzip data .bad magic bytes.")
accelvolume_bad_input(gz_crc crc_4x4x4_uint8.raw.gz
  "corrupt gzip data .* after 64 of 64 bytes .zlib: incorrect data check.")
accelvolume_bad_input(gz_garbage_after_header garbage_4x4x4_uint8.raw.gz "corrupt gzip data")
accelvolume_bad_input(gz_trailing_bytes trailing_4x4x4_uint8.raw.gz
  "trailing bytes after the gzip stream")
accelvolume_bad_input(gz_bomb bomb_1024x1024x2048_float64.raw.gz
  "has only [0-9]+ compressed bytes, too few for 1024x1024x2048 float64 .17179869184 bytes")

# MetaImage headers.
foreach (case IN ITEMS
    "no_dimsize|DimSize must be 3 positive integer.s., one per axis, got ''"
    "negative_dimsize|DimSize must be 3 positive integer.*got '2 -2 2'"
    "zero_dimsize|got '2 0 2'"
    "text_dimsize|got '2 two 2'"
    "huge_dimsize|refusing 100000x100000x100000: more than 2.31 voxels"
    "overflow_dimsize|refusing 3000000000x3000000000x3000000000"
    "ndims4|NDims must be 1, 2 or 3, got '4'"
    "bad_elementtype|unsupported scalar type 'MET_BOGUS'"
    "ulong_elementtype|unsupported scalar type 'MET_ULONG'"
    "missing_datafile|data file .*nothere.raw' named in .* does not exist"
    "short_datafile|size mismatch: .*data4.raw' has 4 data bytes but 2x2x2 uint8 needs 8 bytes"
    "no_elementdatafile|no ElementDataFile"
    "channels3|only single-component volumes are supported for now .* has 3 components"
    "channels_negative|ElementNumberOfChannels must be a positive integer, got '-3'"
    "duplicate_key|'DimSize' appears twice"
    "zero_spacing|has spacing 0 0 0 and origin 0 0 0"
    "list|multi-file data"
    "binary|malformed MetaImage header .* at line 1")
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 name)
  list(GET case 1 regex)
  accelvolume_bad_input(mhd_${name} ${name}.mhd "${regex}")
endforeach ()
accelvolume_bad_input(mhd_folder folder.mhd "cannot open .*folder.mhd': not a readable file")
accelvolume_bad_input(mha_compressed_bomb compressed_bomb.mha
  "has only 26 compressed bytes, too few for 1024x1024x2048 float64")
accelvolume_bad_input(mha_compressed_corrupt compressed_corrupt.mha
  "corrupt compressed data .* after 0 of 8 bytes")
accelvolume_bad_input(mha_compressed_short compressed_short.mha
  "decompresses to 10 bytes but 20x20x20 uint8 needs 8000 bytes")
accelvolume_bad_input(mha_compressed_truthy compressed_truthy.mha
  "corrupt compressed data .* after 0 of 8 bytes")
accelvolume_bad_input(mha_compressed_unsized compressed_unsized.mha
  "CompressedData needs a CompressedDataSize")

# NRRD headers (attached .nrrd, detached .nhdr).
foreach (case IN ITEMS
    "bad_magic.nrrd|missing NRRD magic"
    "no_sizes.nrrd|no 'sizes' field"
    "sizes_before_dimension.nrrd|'sizes' before 'dimension'"
    "bzip2.nrrd|unsupported NRRD encoding 'bzip2'"
    "uint64.nrrd|unsupported scalar type 'uint64'"
    "short.nrrd|has 20 data bytes but 10x2x2 uint8 needs 40 bytes"
    "dimension1.nrrd|need 2 or 3 spatial axes, got 1"
    "ascii_attached.nrrd|NRRD ASCII data in the header's own file is not supported"
    "gzip_corrupt.nrrd|corrupt gzip data .*incorrect data check"
    "gzip_short.nrrd|decompresses to 10 bytes but 10x2x2 uint8 needs 40 bytes"
    "huge_sizes.nrrd|refusing 100000x100000x100000"
    "rgb.nrrd|has 3 components"
    "nan_spacing.nrrd|axis 0 has spacing nan"
    "empty_datafile.nhdr|empty 'data file'"
    "detached_missing.nhdr|data file .*nothere.raw' named in .* does not exist"
    "detached_short.nhdr|data4.raw' has 4 data bytes but 10x2x2 uint8 needs 40 bytes"
    "detached_none.nhdr|a detached header needs a 'data file' field"
    "pattern.nhdr|multi-file data"
    "no_final_newline.nhdr|its last header line has no line break")
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 file)
  list(GET case 1 regex)
  string(REPLACE "." "_" name "${file}")
  accelvolume_bad_input(nrrd_${name} ${file} "${regex}")
endforeach ()

# VTK XML image data and anything else.
foreach (case IN ITEMS
    "not_xml.vti|cannot read .*not_xml.vti': Error parsing XML"
    "truncated.vti|cannot read .*truncated.vti': Error parsing XML"
    "huge_extent.vti|WholeExtent: refusing 100000x100000x100000: more than 2.31 voxels"
    "big_extent.vti|too few for its 1024x1024x2048 extent"
    "zero_spacing.vti|has spacing 0 0 0"
    "negative_components.vti|NumberOfComponents '-3' is not between 1 and 4096"
    "unknown.xyz|unknown file extension"
    "missing.raw|cannot open .*missing.raw': no such file")
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 file)
  list(GET case 1 regex)
  string(REPLACE "." "_" name "${file}")
  accelvolume_bad_input(other_${name} ${file} "${regex}")
endforeach ()

# A datasets.json next to a raw file whose 1 MiB string crashed the old std::regex parser: the
# sidecar is optional metadata, so the render must succeed (and take its spacing from it).
accelvolume_cli_test(badinput_sidecar_long_string
  ARGS render --input "${_av_bad}/sidecar/scan_4x4x4_uint8.raw" --size 32 32 --quiet
       --stats @WORK@/stats.json
  VARS STATS=stats.json)
set_tests_properties(accelvolume.cli.badinput_sidecar_long_string PROPERTIES
  LABELS "cli;badinput" FIXTURES_REQUIRED AccelVolumeBadInputs TIMEOUT 120)
# Control: the good inputs of every format render, so the refusals above are not blanket ones.
foreach (file IN ITEMS good_4x4x4_uint8.raw good_4x4x4_uint8.raw.gz good.mhd good.nrrd good.nhdr
    good.vti)
  string(REPLACE "." "_" name "${file}")
  accelvolume_cli_test(badinput_control_${name}
    ARGS render --input "${_av_bad}/${file}" --size 32 32 --quiet)
  set_tests_properties(accelvolume.cli.badinput_control_${name} PROPERTIES
    LABELS "cli;badinput" FIXTURES_REQUIRED AccelVolumeBadInputs TIMEOUT 120)
endforeach ()
