"""Where the benchmarks' numbers come from: repository paths and manuals, cited beside
every parameter and digitised point (the papers themselves were not read)."""

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
