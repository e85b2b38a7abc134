#!/bin/sh
# Downloads the STEP corpus of examples/bench_step.rs into DIR and checks the SHA-256 of every file.
# Usage: bench/fetch_step_corpus.sh DIR
set -eu
dir=${1:?usage: $0 DIR}
mkdir -p "$dir"
get() { # name sha256 repo commit path
  curl -fsSL "https://raw.githubusercontent.com/$3/$4/$5" -o "$dir/$1"
  echo "$2  $dir/$1" | sha256sum -c --quiet -
}
get '01_openvsp_777-200lr.step' 1696ba6598eea25fac8269c2fd185ec5bf1653f8afe85fb6b0670f12a4a2ceec 'trelau/AFEM' 48455e5d6545f78bc8add8a321e3dc833ca6e44b 'models/777-200LR.stp'
get '02_openvsp_777-200lr-nosplit.step' adb75d100a2ffe2a7287a33802ae5b4b7560643a5c5e8ffc25b9db115e8af89a 'trelau/AFEM' 48455e5d6545f78bc8add8a321e3dc833ca6e44b 'models/777-200LR_nosplit.stp'
get '03_openvsp_supersonic.step' 3b953917d17fe242a852802f8aa8eceb037d7a5e85e66db120206da89f67e2d2 'trelau/AFEM' 48455e5d6545f78bc8add8a321e3dc833ca6e44b 'models/supersonic.stp'
get '04_openvsp_simple-wing.step' fc4a3465a8ed6ee7556614bbc383e83a0735b5dac24703becf27a996aae8bc19 'trelau/AFEM' 48455e5d6545f78bc8add8a321e3dc833ca6e44b 'models/simple_wing.stp'
get '05_openvsp_wing-thick-te.step' 597088783ed0f03ff60b7f5bfddef62170e3f2c73dda63bb142117e3a4b1311d 'trelau/AFEM' 48455e5d6545f78bc8add8a321e3dc833ca6e44b 'test/test_io/vsp_wing_thick_TE1_v3.5.0.stp'
get '06_onshape_777-200lr.step' 8d400513c016700fa8aab72c75f34b884ad5ab69747a3bb98fcb5828d241156c 'trelau/AFEM' 48455e5d6545f78bc8add8a321e3dc833ca6e44b 'models/777-200LR_Onshape.step'
get '07_opencascade_b737-wing.step' f6dc897e2649d70cf0f6d43651fa7b823d8a4fccebf8cf7e9b86de27baba6148 'trelau/AFEM' 48455e5d6545f78bc8add8a321e3dc833ca6e44b 'models/B737_wing_GrabCAD.step'
get '08_onshape_wing-fuselage.step' 472b19aa5c272d393b0016b092acd60ef5669c998365c7402e04fae9964f9a1c 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'benchmarks/step/wing_fuselage.step'
get '09_stdeveloper_rhino-fusee.step' 10c201b8b406a756617113ec6848556de17ca8be60c5a20e5f278115c5deaf18 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'benchmarks/statreport/917_fusee.stp'
get '10_ansa_t106-cascade.step' 97639f28e65c1c81d0c4af812bf57e2652003f88119d2363690e68da9d836eb2 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'benchmarks/step/mesh_T106_V3.step'
get '11_psstep_laufrad-impeller.step' e6003effb8d36766df12511ab37932096dcd002cba7ced2f1e0a60b6b2ff6352 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'benchmarks/step/1385_Laufrad_1000.stp'
get '12_catia5_ventilator.step' 19a11c6949aff4d003a4750d0d9f7e4ee21ab12401dfb07bd97350777266e4d5 'tpaviot/pythonocc-demos' 8158b217efc313889162e7c4dfefba87078d1270 'assets/models/Ventilator.stp'
get '13_catia5_kurbelwelle.step' e72b0f347184fbaad01cbbfe5eeaa6216106423bf24bd444cdb6e7bda546213e 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'benchmarks/statreport/Kurbelwelle.stp'
get '14_catia5_engine-block.step' 03de4b2e21961e1f2b6d2be02c5009702c7924ea8bfcdedba3a007265ceb2e29 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'benchmarks/statreport/Block.stp'
get '15_inventor_angled-clamp.step' 8b7a0f928ff64c6e4e8a9f28f4b7c6934fccf4318e2ca966799b1fd7ddc1c9d1 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'benchmarks/statreport/Angled.step'
get '16_inventor_part-11752.step' c2748324a36018ff1d88cfb0a80946636f29431417b9f1052a0dfc13576b0d41 'tpaviot/pythonocc-demos' 8158b217efc313889162e7c4dfefba87078d1270 'assets/models/11752.stp'
get '17_proe_as1-assembly.step' be1254354f6929a08ce1c8049d4a0a2f4406da4ea283fc4247d009c81976641c 'tpaviot/pythonocc-core' 779838f352694711d60c1567ed3f6e06f3826aa2 'test/test_io/as1_pe_203.stp'
get '18_proe_pump-carter.step' 7f4b85f7abaafd6000c1e96894c6f12ddc5f2419237f39d2e6e75885ff06f1fb 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'benchmarks/statreport/918_pump_carter_sup_21_03_2006.stp'
get '19_nx_geometry-names.step' 707122199062ba1b4f623d8e2e65dc9b03cf33e2f6df87c72c5f69e6a0f9091a 'trelau/AFEM' 48455e5d6545f78bc8add8a321e3dc833ca6e44b 'models/geometry_names.step'
get '20_ug16_io1.step' be588b5eaa6e0471d2c5c05a4ffaf75841bc5cd0680649de2c1fffa7f209ba64 'tpaviot/pythonocc-core' 779838f352694711d60c1567ed3f6e06f3826aa2 'test/test_io/io1-ug-214.stp'
get '21_ug-theorem_as1-ap203e2.step' d40db2ed6f741d2955329f9751c7e3e0a14cbfeb4e11d8338cf110765b9042f9 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'examples/api/as1-tu-203.stp'
get '22_euclid_linkrods.step' 3674e4b01ee0e983c81ed170f0574cda201ad08e0f7b46e05e4f4613400fd5f7 'Open-Cascade-SAS/OCCT' b8f597c677811d1f9f4d8a97f5ae2825c0353a42 'data/step/linkrods.step'
get '23_cobalt_u-joint.step' b607a4886a1820e977885942bfefba94f800f91bb9b97ed867e9339993a733a7 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'benchmarks/step/U_Joint_2.stp'
get '24_solidworks_featuretype.step' 3b161d0fd30d53303d9862c5b66c95f6ee21b75fd0165a3bd68e039a7f154db7 'mikedh/trimesh' a513c0e2cfa6dfbd3121a6dfd8ceb002b9ef55d8 'models/featuretype.STEP'
get '25_solidworks_mve100.step' 25b36c78f79669cee487316d31cfd0310c6de133c3b5a198eb1aaad00c89bbcd 'CadQuery/AnalysisSitus' f3b379ca9158325a21e50fefba8133cab51d9cd9 'data/cad/blends/0082_MVE_100-3_AP203.stp'
get '26_3dexperience_cube.step' 972a46acee4c851219c455bea9f0da61d31af2cb5bcaa7274ff7ead22062d491 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'examples/api/step_boundary_colors.stp'
get '27_fusion360_control-arm.step' ac4f2b51dc47281cc42b65bf73516c96db744b7bc63b74fc17c6cf98c8991797 'CadQuery/AnalysisSitus' f3b379ca9158325a21e50fefba8133cab51d9cd9 'data/cad/blends/0049_control_arm.step'
get '28_fusion360_periodic-u.step' c8f235c05a8abccf66b4fc5c2867c384fc7f52985495c30937fe2dc221f64242 'live-clones/gmsh' fa207ce84b468654a2153f77c8da039688093736 'benchmarks/step/periodic_u_cst.step'
get '29_zoo_exhaust-manifold.step' 940fa21a4ef7aba09f4353aa2e45756819b79342b8ce7b0b4e0288d03c6285bd 'KittyCAD/kcl-samples' c38c9829dd6f4ffa491fc4704e739fa990e76090 'step/exhaust-manifold.step'
get '30_zoo_ball-bearing.step' a779499607e2a96ed5991b00af7db94ac74b0fe0625cccc40706c050541ebbfb 'KittyCAD/kcl-samples' c38c9829dd6f4ffa491fc4704e739fa990e76090 'step/ball-bearing.step'
get '31_cadds_trj3-as1.step' 5903db3119e3bdc4fd0ce40d442e9b2c99a02b78cae2bfef88689e4f1c783e74 'CadQuery/AnalysisSitus' f3b379ca9158325a21e50fefba8133cab51d9cd9 'data/cad/trj3_as1-tc-214.stp'
get '32_c4w3dshop_anc101-ill.step' c0f701f137b4dc5d0862b6d50ae1432cf1c9d6c9601b25708d43d3fba248d4d4 'CadQuery/AnalysisSitus' f3b379ca9158325a21e50fefba8133cab51d9cd9 'data/cad/anomalies/ANC101-ill.stp'
get '33_spatial_boxblend-ap242.step' ca017e63f170c11330c7204bdcad4515abec742388f226c856a2e69df8566b59 'CadQuery/AnalysisSitus' f3b379ca9158325a21e50fefba8133cab51d9cd9 'data/cad/blends/0045_bb_boxblend_03_colored_mirrored.stp'
get '34_spatial_traceparts.step' b0aa2782b1a21889fb9f3d9635f6e068a6d76fe2424ebf9028e58ddb325bf1d7 'CadQuery/AnalysisSitus' f3b379ca9158325a21e50fefba8133cab51d9cd9 'data/cad/blends/0043_204211_grabcad-traceparts.stp'
get '35_rhino8_boxed-sphere.step' c240f4c5f12d2f82dbdf41e88d51a0c686a0c3cab427be7344f2a4401ed00df8 'LLNL/axom_data' 392f998266d779023dfe8cbce6465fe145e71bfc 'quest/step/boxed_sphere.step'
get '36_ideas_dm1.step' 59281108a72af555ef32f05597d38e293ad7667d86ff1baa10241cc76dea8b14 'kovacsv/occt-import-js' 41e470890ae0f9dc69ac50ffd5fc73e03576f4eb 'test/testfiles/cax-if/dm1-id-214.stp'
get '37_cocreate_io1.step' eb234e26bca411a6da39c311e74d5a47b5e7a1248ae589a3a86cd2dee1f91f9b 'kovacsv/occt-import-js' 41e470890ae0f9dc69ac50ffd5fc73e03576f4eb 'test/testfiles/cax-if/io1-cm-214.stp'
get '38_opencascade_repatch-hpdc-ap242.step' b9c04393d7087e3fcd8411a37b04a2051498378c7bfa4e06c316913f87ceff8e 'CadQuery/AnalysisSitus' f3b379ca9158325a21e50fefba8133cab51d9cd9 'data/cad/industrial/repatch-hpdc.stp'
get '39_freecad_level.step' 3c6568f367d7d0eeb09bf6c359bfa28feaa4bc4fa6a34a1ffb5baacacf9acf7f 'CadQuery/AnalysisSitus' f3b379ca9158325a21e50fefba8133cab51d9cd9 'data/cad/blends/0079_level_grabcad-rana.step'
get '40_creo_tail-section.step' f37cef48457bc9bd643513b0e39986a57474321d551faaa292c9a2c826f96983 'CadQuery/AnalysisSitus' f3b379ca9158325a21e50fefba8133cab51d9cd9 'data/cad/industrial/tail_section_asm.stp'
