"""Where the benchmarks' numbers come from (repository paths and manuals, cited beside every
parameter and digitised point; the papers themselves were not read), and the published points
the benchmarks are compared with, as digitised in other DEM codes' repositories. Each
:class:`Measured` is one quantity (:data:`.quantities.QUANTITIES`) against its benchmark's x
quantity."""

from __future__ import annotations

from dataclasses import dataclass

KRATOS = "KratosMultiphysics/Kratos"
LETHE = "chaos-polymtl/lethe"
LETHE_KHARAZ = f"{LETHE} examples/dem/3d-oblique-wall-impact/oblique_wall_impact_postprocessing.py"
KRATOS_CHUNG_OOI = f"{KRATOS} applications/DEMApplication/python_scripts/Chung_Ooi_class.py"
KRATOS_BENCHMARKS = f"{KRATOS} applications/DEMApplication/python_scripts/DEM_benchmarks_class.py"
KRATOS_G2 = f"{KRATOS} applications/DEM_application/test_examples/basic_benchmarks/paper_data/benchmark4_graph2.dat"
KRATOS_G3 = (f"{KRATOS} applications/DEMApplication/tests/DEM3D_chung_ooi_tests/test4_data/paper_data/"
             "benchmark4_graph3.dat")
KRATOS_T10 = f"{KRATOS} applications/DEM_application/test_examples/basic_benchmarks/paper_data/"
MFIX_DEM05 = "MFIX VVUQ manual, DEM05 (https://mfix.netl.doe.gov/doc/vvuq-manual/main/html/dem/dem-05.html)"
YADE_T2 = "Yade Chung-Ooi Test2.py (Angelidakis, Chareyre & Caulk 2023; repository path not resolved)"
YADE_T1 = "Yade Chung-Ooi Test1.py (Angelidakis, Chareyre & Caulk 2023; repository path not resolved)"
PYSPH_T8 = "PySPH Chung-Ooi test 8 example (two differently sized spheres; repository path not resolved)"


@dataclass(frozen=True)
class Measured:
    """Published points of one quantity against the benchmark's x quantity (digitised)."""

    quantity: str
    x: tuple[float, ...]
    values: tuple[float, ...]
    source: str
    label: str


#: Kharaz, Gorham & Salman (2001), alumina on aluminium alloy at 3.9 m/s, against the
#: incidence angle (deg): Chung & Ooi Test 4's measured data.
KHARAZ_2001 = (
    Measured("e_t", (1.84, 3.703, 9.496, 20.012, 30.127, 39.382, 49.694, 60.02),
             (0.79344, 0.74533, 0.67257, 0.59691, 0.68756, 0.77148, 0.84761, 0.90142),
             LETHE_KHARAZ, "Kharaz et al. 2001 (Lethe)"),
    Measured("omega_out", (5.897435897435898, 10.867850098619328, 21.12426035502959, 31.1439842209073,
                           38.95463510848126, 50.23668639053254, 60.098619329388555, 69.96055226824458,
                           78.56015779092702, 84.31952662721893),
             (-134.86238532110102, -261.16207951070345, -573.7003058103976, -612.2324159021407,
              -595.1070336391438, -449.54128440366975, -375.68807339449546, -242.9663608562692,
              -142.35474006116218, -70.6422018348625),
             f"{KRATOS_G2} ('#Experiment' block)", "Kharaz et al. 2001 (Kratos)"),
    Measured("rebound_contact", (2.0997281572207847, 3.9434155319702846, 9.717622556290827, 20.309682809728216,
                                 30.160683905575503, 39.120476602752326, 49.51201496648886, 59.9037955064207,
                                 70.46025585915032, 78.85965284042405, 84.78158734387202),
             (0.7703927492447065, 0.7703927492447065, -1.0574018126888234, -8.53474320241692,
              -2.5528700906344426, 9.909365558912384, 30.015105740181262, 49.95468277945619,
              66.90332326283988, 78.86706948640483, 85.6797583081571),
             f"{KRATOS_G3} ('#Experiment' block)", "Kharaz et al. 2001 (Kratos)"),
    Measured("rebound_centre", (0.016, 2.15, 4.096, 9.826, 20.567, 30.29, 39.535, 49.747, 60.208),
             (0.074, 1.733, 2.962, 6.518, 12.208, 21.67, 32.613, 45.125, 57.474),
             LETHE_KHARAZ, "Kharaz et al. 2001 (Lethe)"),
)

#: Thornton's normalised spin against Psi1 for each restitution e (linear law), from
#: benchmark10_graph2.dat.
_THORNTON_SPIN_POINTS = {
    0.9: ((0.16300940438871503, 0.8840125391849534, 1.8181818181818188, 2.7836990595611284, 3.793103448275861,
           4.8652037617554855, 6.025078369905956, 7.322884012539186, 8.777429467084641, 10.476489028213166),
          (-0.06130814369707083, -0.4175997846310108, -1.2755451313204982, -2.493422472165073,
           -3.550494968579161, -4.427622901931376, -4.941022448273289, -4.97583814860403, -4.98006493649387,
           -4.980529625953563)),
    0.75: ((0.15047021943573702, 0.9655172413793107, 1.981191222570533, 3.03448275862069, 4.137931034482759,
            5.304075235109718, 6.06896551724138, 6.570532915360502, 7.974921630094043, 9.55485893416928,
            11.398119122257054),
           (-0.09959443984486377, -0.5669520058094758, -1.3866299182849589, -2.5892153749909617,
            -3.6539715373419135, -4.550270054308079, -4.918060615967884, -4.956487519258462,
            -4.979845452173423, -4.980277561929301, -4.976952717418795)),
    0.5: ((0.2257053291536053, 1.1661442006269596, 2.357366771159875, 3.5736677115987465, 4.852664576802508,
           6.394984326018809, 7.7115987460815045, 9.341692789968652, 11.197492163009404, 13.35423197492163),
          (-0.16853652256244545, -0.8273770109036269, -1.7160244416367472, -2.872706810386981,
           -3.96814276540527, -4.933465671709185, -5.002747269234956, -4.995535151642803, -4.996042709133834,
           -4.996632573245033)),
    0.25: ((0.27586206896551746, 1.3918495297805644, 2.808777429467085, 4.26332288401254, 5.793103448275863,
            6.6583072100313485, 7.410658307210031, 9.191222570532917, 11.134796238244514, 13.347962382445141),
           (-0.1762081854505333, -0.995913533466072, -2.1985984440047774, -3.3017403563362233,
            -4.374271064850472, -4.891418991852501, -4.972033182142549, -4.9725201629785385,
            -4.9807096716851795, -4.981314968287659)),
}
THORNTON_SPIN = {
    e: Measured("spin_thornton", psi1, spin, f"{KRATOS_T10}benchmark10_graph2.dat ('# e = {e:.2f}')",
                "Thornton (Kratos)")
    for e, (psi1, spin) in _THORNTON_SPIN_POINTS.items()
}
#: Thornton's Psi2 against Psi1 at e = 0.5, Hertzian law (the same file's first block).
THORNTON_PSI2_HERTZIAN = Measured(
    "psi2",
    (0.20444444444444465, 1.137777777777778, 2.3288888888888897, 3.5466666666666686, 4.831111111111112,
     5.760000000000003, 6.195555555555558, 6.3688888888888915, 7.675555555555557, 9.315555555555559),
    (0.01819759305905322, 0.03679541001958997, -0.03599776098516738, -0.5999832073887514,
     -0.7578183599216359, -0.7675566750629743, -0.6417492303386529, -0.5914259725720705,
     0.7179862860341433, 2.3547495102155045),
    f"{KRATOS_T10}bench_10_norm_reb_tang_e_050.dat ('#Hertzian, e = 0.50')", "Thornton, Hertzian (Kratos)")
#: Thornton's Psi2 against Psi1 at e = 0.5, linear law.
THORNTON_PSI2_LINEAR = Measured(
    "psi2",
    (0.20444444444444465, 1.1422222222222222, 2.3244444444444454, 3.551111111111113, 4.831111111111112,
     5.760000000000003, 6.1911111111111135, 6.3688888888888915, 7.675555555555557, 9.320000000000002),
    (0.015048978449481165, -0.013583823117829574, -0.2595479988804943, -0.6786999720123159,
     -0.8176420375034992, -0.7644080604534023, -0.6385992163448102, -0.5945745871816421,
     0.7211349006437153, 2.3515994962216618),
    f"{KRATOS_T10}bench_10_norm_reb_tang_e_050.dat ('#Linear, e = 0.50')", "Thornton, linear (Kratos)")


#: Chung & Ooi Test 5's normalised recoil V'_st/(mu V'_cn) against the incidence V_st/(mu V_cn)
#: (steel, v_n = 5 m/s, mu = 0.3): the finite-element points and the steel curve, as digitised.
CHUNG_OOI_5 = (
    Measured("recoil_co5", (0.006042296072507725, 0.27190332326284006, 0.5861027190332324, 0.8761329305135948,
                            1.1903323262839876, 1.5528700906344413, 1.9154078549848945, 2.3141993957703924,
                            2.7854984894259815, 3.317220543806646, 3.969788519637462, 4.755287009063444,
                            5.758308157099696, 7.123867069486405, 9.117824773413897, 12.356495468277945,
                            12.9607250755287),
             (-0.026666666666666394, -0.026666666666666394, -0.026666666666666394, -0.08000000000000007,
              -0.21333333333333293, -0.3733333333333331, -0.6266666666666669, -0.9466666666666672,
              -1.253333333333333, -1.5199999999999996, -1.7200000000000006, -1.706666666666667,
              -1.2000000000000002, 0.13333333333333375, 2.1466666666666665, 5.426666666666667,
              6.013333333333334),
             f"{KRATOS_T10}benchmark5_graph1.dat ('#FEM' block)", "FEM (Chung & Ooi 2011, Kratos)"),
    Measured("recoil_co5", (0.0664652567975832, 0.3323262839879155, 0.6706948640483383, 1.0090634441087611,
                            1.3353474320241694, 1.6616314199395772, 2.0, 2.350453172205438, 2.990936555891238,
                            3.3413897280966762, 4.006042296072506, 4.996978851963746, 6.0, 9.987915407854985,
                            12.9607250755287),
             (-0.08000000000000007, -0.28000000000000025, -0.49333333333333407, -0.7466666666666661, -1.0,
              -1.2666666666666666, -1.5333333333333332, -1.8133333333333326, -2.4399999999999995,
              -2.6933333333333334, -2.786666666666667, -2.0, -1.0133333333333328, 3.013333333333333,
              6.013333333333334),
             f"{KRATOS_T10}benchmark5_graph1.dat ('#Steel' block)", "steel (Chung & Ooi 2011, Kratos)"),
)

