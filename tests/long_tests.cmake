# The long tier: tests that CI (scripts/test.sh) leaves out to stay within its budget (40 minutes on
# 2 cores for build and tests) and `scripts/test.sh --full` runs with the rest: the tests of 19 s
# or more with kernels compiled cold on the 2-core machine (December 2026, docs/testing.md), and
# the second bin width or depth cap of families whose cases compile kernels of their own. What each
# covers keeps a cheaper test in CI: a sibling case of the same family, or the same integrator on
# other scenes. Read by ctest after the tests are discovered (tests/CMakeLists.txt).

cmake_policy(SET CMP0057 NEW)  # if(IN_LIST) in ctest's scope

# Every integrator keeps its furnaces at one bin width in CI: backward, photon, bpt and forward at
# 10 nm (bpt's mirror too is long), vcm and ppm at 1 nm (ppm: the passive furnace).
set(kasha_long_furnaces
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/ppm_mirror_10nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/ppm_mirror_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/ppm_uv_10nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/ppm_uv_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/ppm_passive_10nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/ppm_fluorescent_10nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/ppm_fluorescent_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/ppm_self_absorption_10nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/vcm_mirror_10nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/vcm_uv_10nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/vcm_passive_10nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/vcm_self_absorption_10nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/vcm_fluorescent_10nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/forward_mirror_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/forward_fluorescent_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/forward_passive_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/forward_self_absorption_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/bpt_mirror_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/ppm_self_absorption_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/backward_fluorescent_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/backward_mirror_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/backward_passive_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/backward_self_absorption_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/backward_uv_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/bpt_fluorescent_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/bpt_passive_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/bpt_self_absorption_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/bpt_uv_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/photon_fluorescent_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/photon_mirror_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/photon_passive_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/photon_self_absorption_1nm"
  "Registry/IntegratorFurnace.EveryBinMatchesTheAnalyticValue/photon_uv_1nm")
# bpt and forward keep their agreement with backward on the sunlit table, the lacquered vase (forward)
# and the pbrt-v4 glass and texture scenes; vcm on every scene; photon and ppm on kasha's own.
set(kasha_long_agreement
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/bpt_glass_caustic"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/bpt_glossy_cornell_box"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/bpt_cornell_box"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/bpt_pbrt_cornell_box"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/bpt_pbrt_rough_metals"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/bpt_fluorescent_print"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/bpt_light_booth_uv_spot"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/bpt_lacquered_vase"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/forward_glass_caustic"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/forward_pbrt_cornell_box"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/forward_glossy_cornell_box"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/forward_cornell_box"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/forward_pbrt_rough_metals"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/forward_fluorescent_print"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/forward_light_booth_uv_spot"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/photon_pbrt_cornell_box"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/photon_pbrt_glass"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/photon_pbrt_rough_metals"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/photon_pbrt_textured"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/ppm_pbrt_cornell_box"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/ppm_pbrt_glass"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/ppm_pbrt_rough_metals"
  "Registry/IntegratorAgreement.RegionsMatchTheReferenceIntegrator/ppm_pbrt_textured")
# Every integrator's depth-capped furnaces keep caps 0 and 3 in CI.
set(kasha_long_depth_caps
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/backward_fluorescent_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/backward_mirror_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/backward_passive_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/bpt_fluorescent_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/bpt_mirror_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/bpt_passive_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/forward_fluorescent_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/forward_passive_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/photon_fluorescent_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/photon_mirror_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/photon_passive_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/ppm_fluorescent_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/ppm_mirror_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/ppm_passive_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/vcm_fluorescent_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/vcm_mirror_cap1"
  "Registry/DepthCapFurnace.EveryBinMatchesTheCappedSeries/vcm_passive_cap1")
# The stiff catalogue keeps its other cases, albedo 0.999 in a box among them.
set(kasha_long_stiff
  "Catalogue/StiffCases.EveryIntegratorMatchesTheReference/mirror_999_box"
  "Catalogue/StiffCases.EveryIntegratorMatchesTheReference/albedo_9999_sphere"
  "Catalogue/StiffCases.EveryIntegratorMatchesTheReference/self_absorption_999"
  "Catalogue/StiffCases.EveryIntegratorMatchesTheReference/mixture_999_box"
  "Catalogue/StiffCases.EveryIntegratorMatchesTheReference/mirror_mixture_999_sphere"
  "Catalogue/StiffCases.EveryIntegratorMatchesTheReference/uv_only_xyz"
  "Catalogue/StiffCases.EveryIntegratorMatchesTheReference/bins_40nm"
  "Catalogue/StiffCases.EveryIntegratorMatchesTheReference/single_bin"
  "Catalogue/StiffCases.EveryIntegratorMatchesTheReference/image_1000x1")
# Agreement and weight-sum studies whose capability CI checks more cheaply elsewhere (the furnaces,
# the agreement cases above, the pbrt-v4 Cornell box, media and fog references, the medium furnaces
# and slab); bench's full record (CI keeps its interrupted run, validation and bad command lines).
set(kasha_long_other
  "RoughInterface.LightTracingAgreesWithBackwardOnRoughSurfaces"
  "Scenes/PbrtReference.RegionMeansMatchPbrtV4WithinOnePercent/rough_metals"
  "Scenes/PbrtReference.RegionMeansMatchPbrtV4WithinOnePercent/rough_textures"
  "Vcm.BptWeightsSumToOnePerPathLength"
  "Vcm.CausticMergesWeightsSumToOnePerPathLength"
  "Vcm.BptAgreesWithBackwardUnderADistantLightOnNormalMappedSurfaces"
  "Converge.FurnaceSlopesMatchTheory"
  "LayeredMetal.EveryIntegratorAgreesWithBackward"
  "SphereLight.EveryIntegratorAgreesWithTriangleSampling"
  "Medium.ForwardPhotonAndVcmAgreeWithBackwardOnTonicWaterUnderAUvSpot"
  # dye in glass: PbrtReference/media's dye-in-glass region and the dye slab in every integrator
  "Medium.EveryIntegratorAgreesWithBackwardOnDyeInGlass"
  "Colorimetry/Hemisphere.RenderShowsColorimetryXyz/ppm"
  "Integrators/MpiRender.TwoAndThreeRanksWriteTheOneProcessFile/vcm"
  "RoughnessTexture.EachSquareRendersAsItsConstantRoughness"
  "ShadingNormals.NoLightLeaksThroughTheSurface"
  "ShadingNormals.AFloorIsLitAsItsShadingNormalFacesTheLight"
  "Mix.FluorescentMixAgreesFromBothEnds"
  "Mix.GlossyAndFluorescentMixesAgreeWithBackward"
  "Mix.MergingOnAMirrorMixIsWarnedAbout"
  "NormalMaps.AMapOfTheUnperturbedNormalChangesNothing"
  "MirrorCaustic.PhotonMappingAndVcmMatchBackwardOnTheTileSeenInTheMirror"
  "Vcm.VcmWeightsSumToOnePerPathLength"
  "Vcm.AWeightWithADensityDroppedFails"
  "EdgeCorrection.MergesMatchBackwardBesideARim"
  "SphereLight.BptWeightsSumToOneWithASphereLight"
  "Bench.RunsAloneAndOnTwoQueuesGiveARecordOfTheDocumentedSchema")
# A parameterised test's ctest name ends in "  # GetParam() = ...": matched on what comes before.
set(kasha_long ${kasha_long_furnaces} ${kasha_long_agreement} ${kasha_long_depth_caps}
               ${kasha_long_stiff} ${kasha_long_other})
set(kasha_long_found 0)
foreach(test IN LISTS kasha_tests_TESTS)
  string(REGEX REPLACE "  # GetParam\\(\\) = .*$" "" name "${test}")
  if(name IN_LIST kasha_long)
    set_tests_properties("${test}" PROPERTIES LABELS long)
    math(EXPR kasha_long_found "${kasha_long_found} + 1")
  endif()
endforeach()
# A renamed test would drop out of the tier unnoticed.
list(LENGTH kasha_long kasha_long_count)
if(NOT kasha_long_found EQUAL kasha_long_count)
  message(FATAL_ERROR "tests/long_tests.cmake: ${kasha_long_found} of its ${kasha_long_count} tests found")
endif()
