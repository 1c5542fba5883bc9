# The same scene given as PFM, as OpenEXR (depth in channel Y, normals in R,G,B) or as 16-bit PNG
# depth must give the same AO: EXR stores the same floats, so the AO must be identical; the 16-bit
# PNG holds depth on a 1/65535 grid (value/65535 = the raw depth), close to but not exactly the
# float depth, so its AO may differ a little (mean below 1/255). Output formats are read back:
# .exr (float, channel Y) must equal .pfm exactly, and a --png16 image must be 16-bit.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
tool(ignored convert ${ROOM}/depth.pfm ${WORK}/depth.exr)
tool(ignored convert ${ROOM}/normals.pfm ${WORK}/normals.exr)
tool(ignored convert ${ROOM}/depth.pfm ${WORK}/depth16.png)
set(CAM --camera ${ROOM}/camera.json --validate --quality high)

cacao_ok(pfm --depth ${ROOM}/depth.pfm --normals ${ROOM}/normals.pfm ${CAM} -o ${WORK}/pfm.pfm)
cacao_ok(exr --depth ${WORK}/depth.exr --normals ${WORK}/normals.exr ${CAM} -o ${WORK}/exr.exr)
cacao_ok(png --depth ${WORK}/depth16.png --normals ${ROOM}/normals.pfm ${CAM} --png16 -o ${WORK}/png.png)

mean_abs_diff(d_exr ${WORK}/pfm.pfm ${WORK}/exr.exr)
expect_between("EXR inputs and output vs PFM, mean |diff|" ${d_exr} 0 0)
tool(info info ${WORK}/png.png)
if(NOT info STREQUAL "160 90 1 16")
  message(FATAL_ERROR "--png16 output is '${info}', expected 160x90, 1 channel, 16 bits")
endif()
mean_abs_diff(d_png ${WORK}/pfm.pfm ${WORK}/png.png)
expect_between("16-bit PNG depth vs float depth, mean |AO diff|" ${d_png} 0 0.0039)
