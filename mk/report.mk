# make report: the blog companion (tests/report/report.py, its modules report_*.py beside it). Renders every complete
# official scene and our own with culling off and on, measures float against double,
# ShadowRayEpsilon x0.1 / x10, --min-weight 0, MaxRecursionDepth 0..8 and BVH build
# variants, and assignment 3's convergence, samplers, adaptive sampling and feature costs
# (report_convergence.py: converged images cached in build/report/converged), and writes
# report/ (gitignored): index.md, index.html, chart.svg, convergence.svg, report.json, img/.
#   make report                       3 processes per configuration (about 4 minutes on 2 cores)
#   make report-quick                 1 process of --repeat 3, fewer BVH variants, no 1M-triangle mesh
#                                     (about 2 minutes)
#   make report REPORT_ARGS="--runs 5 --threads 1"     (see report.py --help)
# One raytracer measures both precisions (--precision); the course's files come from
# ../shared or $$RT_SHARED_DIR.
REPORT_WORK    := build/report
REPORT_IMGDIFF := $(REPORT_WORK)/imgdiff
REPORT_GEN     := build/bench/gen_mesh
REPORT_ARGS    ?=
REPORT_RUN      = python3 tests/report/report.py --bin ./raytracer --imgdiff $(REPORT_IMGDIFF) --rtdiff ./rtdiff \
                  --gen-mesh $(REPORT_GEN) --work $(REPORT_WORK) --out report $(if $(RT_SHARED_DIR),--shared $(RT_SHARED_DIR))

$(REPORT_IMGDIFF): tests/report/imgdiff.cpp
	@mkdir -p $(dir $@)
	$(CXX) -O2 -std=c++17 -Wall -Wextra -o $@ $< -lstb

.PHONY: report report-quick
report: raytracer rtdiff $(REPORT_IMGDIFF) $(REPORT_GEN)
	@mkdir -p report
	$(REPORT_RUN) $(REPORT_ARGS)

report-quick: raytracer rtdiff $(REPORT_IMGDIFF)
	@mkdir -p report
	$(REPORT_RUN) --quick $(REPORT_ARGS)

# report.py's own unit tests (its timings, ratio marks and HTML) run with `make test`.
.PHONY: test-report
test: test-report
test-report:
	@echo "== report.py's unit tests" && python3 -B tests/report/test_report.py
