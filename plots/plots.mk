# plots/plots.mk: `make plots` (the top Makefile runs `$(MAKE) -f plots/plots.mk`).
# Scene -> one database per run -> merged databases -> analysis -> figures and tables in
# $(OUT); only what changed is rebuilt (every run depends on $(HAFF), its scene file and
# plots/scripts/run.sh; every figure on its data and its .gp script; a change of the
# parameters below rewrites $(DATA)/config.txt, which the merged databases depend on).
# plots/README.md says what each output is; this build's numbers go to $(OUT)/README.md.
# Every figure is written as PNG, SVG and PDF in one style (plots/style.gp, loaded by every .gp),
# and $(OUT)/index.html shows them all with Tables I-II on one page (plots/scripts/report.py).
#
#   make plots                 default ensembles (2.5 minutes with make -j2 on 2 idle cores; 13
#                              minutes on 2 cores shared with 7 other builds)
#   make plots PAPER=1         larger ensembles and longer runs
#   make plots ETA=0.1         another area fraction (runs go to their own folder)
#   make -f plots/plots.mk plots-clean   removes $(OUT)
# Also included: plots/fmean.mk (fig4, fmean), plots/rods.mk (the rod paper's figures) and
# plots/shapes.mk (cooling and <f> of rigid clusters of disks; build/plots/shapes, built by the
# top Makefile's `plots`).
.SUFFIXES:
.DELETE_ON_ERROR:
SHELL   := /bin/bash
HAFF    ?= bin/haff
OUT     ?= plots/out
GNUPLOT ?= gnuplot
SCRIPTS := plots/scripts
# the one style every figure loads (fonts, lines, palette, terminals by extension)
STYLE   := plots/style.gp
DATA    := $(OUT)/data

# --- parameters ------------------------------------------------------------------------------
# area fraction of every dimer and disk scene
ETA        ?= 0.05
# dimers (and disks) in the Tables I-II / Figs. 2-3 runs
NDIM       ?= 900
ALPHAS     ?= 1 0.99 0.98 0.95 0.9 0.85 0.8
AOVERD     ?= 0.5 1 1.5
# Tables I-II: the paper's alphas; box side TAB_LFRAC x the HCS's critical size L_c(alpha) at
# alpha >= TAB_ALPHA_LOW (at most NDIM bodies), TAB_LFRAC_LOW x L_c below it and for the
# ALPHA:A groups of TAB_LOW: the largest of the two boxes whose measured total error of D_e is
# <= 0.015 (plots/README.md, "Boxes of the tables": at 0.7 L_c alpha 0.9, a/d 1.5 had 0.017)
TAB_ALPHAS ?= 1 0.99 0.98 0.95 0.9 0.85
TAB_LFRAC  ?= 0.7
TAB_LFRAC_LOW ?= 0.5
TAB_ALPHA_LOW ?= 0.9
TAB_LOW    ?= 0.9:1.5
# a/d near 2: a disk of another dimer fits the gap between a dimer's disks (exactly at 2d):
# these runs (alpha = GAP_ALPHA, NRUNS seeds) show why a = 2d is not in the tables (README)
GAP_A      ?= 1.9 2 2.1
GAP_ALPHA  ?= 0.9
# long runs (NRUNS seeds, a = d) that go on until the homogeneity detector cuts them (README)
LONG_ALPHA ?= 0.8
LONG_CPD   ?= 300
# the hard-disk reference (Fig. 2 dashed, Table I a/d = 0)
DISK_ALPHAS ?= 0.95 0.9
# Figs. 2-3 show these at a/d = FIG2_A
FIG2_ALPHAS ?= 0.98 0.95 0.9 0.8
FIG2_A     ?= 1
# run length at alpha = 1
ELASTIC_CPD ?= 200
# errcost: D_e at this (alpha, a/d)
ERR_ALPHA  ?= 0.9
ERR_A      ?= 1
# hcs: state measures against cpd, disks at HCS_ALPHA in a stable and an unstable box (N)
HCS_ALPHA  ?= 0.8
HCS_STABLE ?= 200
HCS_UNSTABLE ?= 3600
HCS_CPD    ?= 160
# errcost's stable box: as many dimers (a = ERR_A, alpha = ERR_ALPHA) as stay below the HCS's
# critical size (docs/analysis.md); the NDIM box is the other one
ERR_NSTABLE ?= 200
# elastic runs with logged collisions for <f> (fmean_vs_engine)
FMEAN_A    ?= 0.5 1 2
ifeq ($(PAPER),1)
# runs (seeds 1..NRUNS) per (alpha, a/d)
NRUNS      ?= 20
# Tables I-II: as many body-runs per group as TAB_RUNS (alpha >= TAB_ALPHA_LOW, not in TAB_LOW) or
# TAB_RUNS_LOW runs of NDIM bodies
TAB_RUNS   ?= 40
TAB_RUNS_LOW ?= 80
# runs stop at (1 - alpha^2) cpd = XMAX
XMAX       ?= 24
ERR_RUNS   ?= 128
FIG6_RUNS  ?= 20
ERR_CPD    ?= 20 40 80 160 320
FIG5_CPD   ?= 300
MC_SAMPLES ?= 10000000
else
NRUNS      ?= 8
TAB_RUNS   ?= 16
TAB_RUNS_LOW ?= 32
XMAX       ?= 16
ERR_RUNS   ?= 32
FIG6_RUNS  ?= 8
ERR_CPD    ?= 20 40 80 160
FIG5_CPD   ?= 100
MC_SAMPLES ?= 1000000
endif

# run databases, in a folder per (ETA, NDIM, XMAX): runs of other settings stay and are reused
RD      := $(DATA)/runs/eta$(ETA)-n$(NDIM)-x$(XMAX)
SEEDS   := $(shell seq 1 $(NRUNS))
ESEEDS  := $(shell seq 1001 $$((1000 + $(ERR_RUNS))))
COMMON  := --set system.area_fraction=$(ETA)
CONFIG  := ETA=$(ETA) NDIM=$(NDIM) NRUNS=$(NRUNS) TAB_RUNS=$(TAB_RUNS) TAB_RUNS_LOW=$(TAB_RUNS_LOW) TAB_ALPHAS=$(TAB_ALPHAS) TAB_LFRAC=$(TAB_LFRAC) TAB_LFRAC_LOW=$(TAB_LFRAC_LOW) TAB_ALPHA_LOW=$(TAB_ALPHA_LOW) TAB_LOW=$(TAB_LOW) XMAX=$(XMAX) ALPHAS=$(ALPHAS) AOVERD=$(AOVERD) GAP_A=$(GAP_A) GAP_ALPHA=$(GAP_ALPHA) \
           LONG_ALPHA=$(LONG_ALPHA) LONG_CPD=$(LONG_CPD) \
           DISK_ALPHAS=$(DISK_ALPHAS) FIG2_ALPHAS=$(FIG2_ALPHAS) FIG2_A=$(FIG2_A) \
           ELASTIC_CPD=$(ELASTIC_CPD) ERR_ALPHA=$(ERR_ALPHA) ERR_A=$(ERR_A) ERR_RUNS=$(ERR_RUNS) \
           ERR_CPD=$(ERR_CPD) FIG5_CPD=$(FIG5_CPD) FMEAN_A=$(FMEAN_A) MC_SAMPLES=$(MC_SAMPLES) \
           HCS_ALPHA=$(HCS_ALPHA) HCS_STABLE=$(HCS_STABLE) HCS_UNSTABLE=$(HCS_UNSTABLE) HCS_CPD=$(HCS_CPD) \
           ERR_NSTABLE=$(ERR_NSTABLE) FIG6_RUNS=$(FIG6_RUNS)
# $(DATA)/config.txt is rewritten only when the parameters change
$(shell mkdir -p $(DATA); echo '$(CONFIG)' | cmp -s - $(DATA)/config.txt || echo '$(CONFIG)' > $(DATA)/config.txt)

PAPER_FIGS := fig1 fig2 fig3 fig5 fig6 errcost hcs
TABLES  := $(OUT)/table1.tsv $(OUT)/table1.md $(OUT)/table2.tsv $(OUT)/table2.md \
           $(OUT)/fmean_vs_engine.tsv
.PHONY: plots plots-clean
plots: $(foreach f,$(PAPER_FIGS),$(OUT)/$(f).png $(OUT)/$(f).svg $(OUT)/$(f).pdf) $(TABLES) \
       $(OUT)/README.md fmean-plots rods-plots shapes-plots species-plots $(OUT)/index.html

FMEAN_T1 := $(OUT)/table1.tsv
include plots/fmean.mk
include plots/shapes.mk
include plots/species.mk
include plots/rods.mk

# stop_cpd for alpha $(1): (1 - alpha^2) cpd = XMAX, ELASTIC_CPD at alpha = 1
stopcpd = $(shell awk 'BEGIN { a = $(1); printf "%.6g", a == 1 ? $(ELASTIC_CPD) : $(XMAX) / (1 - a * a) }')

# RUN(db, scene, haff run options): one database per run (plots/scripts/run.sh)
define RUN
$(1): $(2) $(HAFF) $(SCRIPTS)/run.sh
	@echo "run  $$@"
	@$(SCRIPTS)/run.sh $(HAFF) $$@ $(2) $(COMMON) $(3)
endef

# --- Tables I-II, Figs. 2-3: dimers on the (alpha, a/d) grid, disks as the reference ----------
dimer_db = $(RD)/dimers-a$(1)-al$(2)-s$(3).db
disk_db  = $(RD)/disks-al$(1)-s$(2).db
$(foreach a,$(AOVERD),$(foreach al,$(ALPHAS),$(foreach s,$(SEEDS),$(eval $(call RUN,$(call \
  dimer_db,$(a),$(al),$(s)),scenes/paper-dimers.ini,--set dimers.count=$(NDIM) --set \
  dimers.a=$(a) --set dimers.alpha=$(al) --set run.stop_cpd=$(call stopcpd,$(al)) --seed $(s))))))
$(foreach al,$(DISK_ALPHAS),$(foreach s,$(SEEDS),$(eval $(call RUN,$(call disk_db,$(al),$(s)),\
  scenes/paper-disks.ini,--set disks.count=$(NDIM) --set disks.alpha=$(al) --set \
  run.stop_cpd=$(call stopcpd,$(al)) --seed $(s)))))

# Tables I-II: each (alpha, a/d) in its own box inside the HCS (plots/README.md, "Boxes of the
# tables"). At the fixed area fraction ETA (so that nu0 and chi stay those of the paper's
# density) the box side is TAB_LFRAC (alpha >= TAB_ALPHA_LOW, not in TAB_LOW) or TAB_LFRAC_LOW x L_c(alpha), the hydrodynamic critical size of the disk
# HCS (docs/analysis.md: L_c = sqrt(2 pi D_e eta* / (1 - alpha^2)) / (n sigma chi), D_e = 2, chi
# of Henderson), N = ETA L^2 / (area of one body in d^2), at most NDIM (all of alpha = 1, 0.99,
# 0.98). tab_n(alpha, a/d): N, a/d = 0 for disks; tab_runs(N, alpha, a/d): TAB_RUNS (alpha >= TAB_ALPHA_LOW, not in TAB_LOW) or
# TAB_RUNS_LOW x NDIM / N runs (as many body-runs as that many runs of NDIM), at least NRUNS.
tab_low = $(if $(filter $(1):$(2),$(TAB_LOW)),1,0)
tab_n = $(shell awk 'BEGIN { al = $(1); a = $(2); eta = $(ETA); f = $(1) >= $(TAB_ALPHA_LOW) && !$(call tab_low,$(1),$(2)) ? $(TAB_LFRAC) : $(TAB_LFRAC_LOW); cap = $(NDIM); \
  if (al >= 1) { print cap; exit } pi = 3.14159265358979; \
  area = a == 0 ? pi / 4 : a >= 1 ? pi / 2 : pi / 2 - (0.5 * atan2(sqrt(1 - a * a), a) - a / 2 * sqrt(1 - a * a)); \
  es = 1 / ((7 - 3 * al) * (1 + al) / 8 - (1 - al * al) / 4); chi = (1 - 7 * eta / 16) / (1 - eta) ^ 2; \
  lc = sqrt(2 * pi * 2 * es / (1 - al * al)) / (4 * eta / pi * chi); \
  n = int(eta * (f * lc) ^ 2 / area); print n < cap ? n : cap }')
tab_runs = $(shell awk 'BEGIN { r = int((($(2) >= $(TAB_ALPHA_LOW) && !$(call tab_low,$(2),$(3)) ? $(TAB_RUNS) : $(TAB_RUNS_LOW)) * $(NDIM) + $(1) - 1) / $(1)); print (r > $(NRUNS) ? r : $(NRUNS)) }')
# per group: TN_a_al, TR_a_al (dimers), TN_0_al, TR_0_al (disks)
$(foreach a,$(AOVERD),$(foreach al,$(TAB_ALPHAS),$(eval TN_$(a)_$(al) := $(call tab_n,$(al),$(a)))\
  $(eval TR_$(a)_$(al) := $(call tab_runs,$(TN_$(a)_$(al)),$(al),$(a)))))
$(foreach al,$(DISK_ALPHAS),$(eval TN_0_$(al) := $(call tab_n,$(al),0))$(eval TR_0_$(al) := $(call \
  tab_runs,$(TN_0_$(al)),$(al),0)))
# the run of seed s: in the NDIM box the grid's own run (seeds 1..NRUNS), else its own file
tab_dimer_db = $(if $(filter $(NDIM),$(TN_$(1)_$(2))),$(call dimer_db,$(1),$(2),$(3)),$(RD)/dimers-a$(1)-al$(2)-n$(TN_$(1)_$(2))-s$(3).db)
tab_disk_db = $(if $(filter $(NDIM),$(TN_0_$(1))),$(call disk_db,$(1),$(2)),$(RD)/disks-al$(1)-n$(TN_0_$(1))-s$(2).db)
tab_seeds = $(if $(filter $(NDIM),$(1)),$(filter-out $(SEEDS),$(shell seq 1 $(2))),$(shell seq 1 $(2)))
$(foreach a,$(AOVERD),$(foreach al,$(TAB_ALPHAS),$(foreach s,$(call tab_seeds,$(TN_$(a)_$(al)),$(TR_$(a)_$(al))),\
  $(eval $(call RUN,$(call tab_dimer_db,$(a),$(al),$(s)),scenes/paper-dimers.ini,--set \
  dimers.count=$(TN_$(a)_$(al)) --set dimers.a=$(a) --set dimers.alpha=$(al) --set \
  run.stop_cpd=$(call stopcpd,$(al)) --seed $(s))))))
$(foreach al,$(DISK_ALPHAS),$(foreach s,$(call tab_seeds,$(TN_0_$(al)),$(TR_0_$(al))),$(eval $(call \
  RUN,$(call tab_disk_db,$(al),$(s)),scenes/paper-disks.ini,--set disks.count=$(TN_0_$(al)) --set \
  disks.alpha=$(al) --set run.stop_cpd=$(call stopcpd,$(al)) --seed $(s)))))
TABLE_DBS := $(foreach a,$(AOVERD),$(foreach al,$(TAB_ALPHAS),$(foreach s,$(shell seq 1 $(TR_$(a)_$(al))),\
  $(call tab_dimer_db,$(a),$(al),$(s))))) $(foreach al,$(DISK_ALPHAS),$(foreach s,$(shell seq 1 \
  $(TR_0_$(al))),$(call tab_disk_db,$(al),$(s))))
# the box (N) and runs of every table group, a TSV on stdout (test_plots checks N against L_c)
.PHONY: tables-boxes
tables-boxes:
	@printf 'species\talpha\ta_over_d\tN\truns\n'
	@printf '%s\n' $(foreach a,$(AOVERD),$(foreach al,$(TAB_ALPHAS),dimers,$(al),$(a),$(TN_$(a)_$(al)),$(TR_$(a)_$(al)))) \
	  $(foreach al,$(DISK_ALPHAS),disks,$(al),0,$(TN_0_$(al)),$(TR_0_$(al))) | tr , '\t'

GAP_DBS   := $(foreach a,$(GAP_A),$(foreach s,$(SEEDS),$(call dimer_db,$(a),$(GAP_ALPHA),$(s))))
$(foreach a,$(filter-out $(AOVERD),$(GAP_A)),$(foreach s,$(SEEDS),$(eval $(call RUN,$(call \
  dimer_db,$(a),$(GAP_ALPHA),$(s)),scenes/paper-dimers.ini,--set dimers.count=$(NDIM) --set \
  dimers.a=$(a) --set dimers.alpha=$(GAP_ALPHA) --set run.stop_cpd=$(call stopcpd,$(GAP_ALPHA)) \
  --seed $(s)))))
LONG_DBS  := $(foreach s,$(SEEDS),$(RD)/long-a1-al$(LONG_ALPHA)-c$(LONG_CPD)-s$(s).db)
$(foreach s,$(SEEDS),$(eval $(call RUN,$(RD)/long-a1-al$(LONG_ALPHA)-c$(LONG_CPD)-s$(s).db,\
  scenes/paper-dimers.ini,--set dimers.count=$(NDIM) --set dimers.alpha=$(LONG_ALPHA) --set \
  run.stop_cpd=$(LONG_CPD) --seed $(s))))
DISK_DBS  := $(foreach al,$(DISK_ALPHAS),$(foreach s,$(SEEDS),$(call disk_db,$(al),$(s))))
FIG23_DBS := $(foreach al,$(FIG2_ALPHAS),$(foreach s,$(SEEDS),$(call dimer_db,$(FIG2_A),$(al),$(s))))

# MERGE(out, inputs): one database with every run of the inputs (plots/scripts/merge.sh)
define MERGE
$(1): $(2) $(HAFF) $(SCRIPTS)/merge.sh $(DATA)/config.txt
	@echo "merge $$@ ($(words $(2)) runs)"
	@$(SCRIPTS)/merge.sh $(HAFF) $$@ $(2)
endef
# (its thousands of inputs exceed the 128 KiB of one shell command line: a list file and xargs)
$(DATA)/tables.db: $(TABLE_DBS) $(HAFF) $(SCRIPTS)/merge.sh $(DATA)/config.txt
	@echo "merge $@ ($(words $(TABLE_DBS)) runs)"
	$(file >$@.list,$(TABLE_DBS))
	@xargs -x -s 1000000 -a $@.list $(SCRIPTS)/merge.sh $(HAFF) $@
	@rm -f $@.list
$(eval $(call MERGE,$(DATA)/fig23.db,$(FIG23_DBS)))
$(eval $(call MERGE,$(DATA)/disks.db,$(DISK_DBS)))
$(eval $(call MERGE,$(DATA)/gap.db,$(GAP_DBS)))
$(eval $(call MERGE,$(DATA)/long.db,$(LONG_DBS)))

$(OUT)/table1.tsv: $(DATA)/tables.db $(HAFF)
	$(HAFF) table1 $< -o $@
$(OUT)/table1.md: $(DATA)/tables.db $(HAFF)
	$(HAFF) table1 $< --md -o $@
$(OUT)/table2.tsv: $(DATA)/tables.db $(HAFF)
	$(HAFF) table2 $< -o $@
$(OUT)/table2.md: $(DATA)/tables.db $(HAFF)
	$(HAFF) table2 $< --md -o $@
# per run: where the homogeneity detector cut the fit (README)
$(DATA)/fits.tsv: $(DATA)/tables.db $(HAFF)
	$(HAFF) haff-fit $< -o $@
$(DATA)/fits-groups.tsv: $(DATA)/tables.db $(HAFF)
	$(HAFF) haff-fit $< --alpha-group -o $@
# a/d near 2 (README): per run its fate
$(DATA)/gap.tsv: $(DATA)/gap.db
	sqlite3 -header -separator $$'\t' $< "SELECT p.file, r.status, round(max(s.t), 4) AS t_end, \
	  max(s.cpd) AS cpd_end, r.events, coalesce(r.message, '') AS message FROM runs r \
	  JOIN plots_runs p ON p.run = r.id JOIN samples s ON s.run = r.id GROUP BY r.id ORDER BY r.id" > $@
$(DATA)/gap-fits.tsv: $(DATA)/gap.db $(HAFF)
	$(HAFF) haff-fit $< -o $@ 2> $(DATA)/gap-fits.err || test $$? = 2 # 2: no run fitted
$(DATA)/long-fits.tsv: $(DATA)/long.db $(HAFF)
	$(HAFF) haff-fit $< -o $@
$(DATA)/energy.tsv: $(DATA)/fig23.db $(HAFF)
	$(HAFF) energy $< -o $@
$(DATA)/energy_disks.tsv: $(DATA)/disks.db $(HAFF)
	$(HAFF) energy $< -o $@

# Fig. 2's mean and spread (s.d.) over the runs per alpha, dimers and disks
$(DATA)/band.tsv: $(DATA)/fig23.db $(SCRIPTS)/energy_band.py
	$(SCRIPTS)/energy_band.py $< > $@
$(DATA)/band_disks.tsv: $(DATA)/disks.db $(SCRIPTS)/energy_band.py
	$(SCRIPTS)/energy_band.py $< disks > $@
$(OUT)/fig2.png $(OUT)/fig2.svg $(OUT)/fig2.pdf: $(OUT)/fig2.%: $(DATA)/energy.tsv $(DATA)/band.tsv $(DATA)/band_disks.tsv plots/fig2.gp $(STYLE)
	$(GNUPLOT) -e "in='$<'; band='$(DATA)/band.tsv'; bandref='$(DATA)/band_disks.tsv'; out='$@'" plots/fig2.gp
# Fig. 3 marks its own groups' flags (haff-fit --alpha-group on fig23.db: the figure's NDIM runs,
# not the tables' boxes, which differ below alpha 0.98 and leave out FIG2_ALPHAS' 0.8), as the
# words ALPHA=FLAG of the groups at a/d = FIG2_A with a flag (the column found by name)
$(DATA)/fig23-groups.tsv: $(DATA)/fig23.db $(HAFF)
	$(HAFF) haff-fit $< --alpha-group -o $@
$(OUT)/fig3.png $(OUT)/fig3.svg $(OUT)/fig3.pdf: $(OUT)/fig3.%: $(DATA)/energy.tsv $(DATA)/fig23-groups.tsv plots/fig3.gp $(STYLE)
	$(GNUPLOT) -e "in='$<'; out='$@'; flagged='$$(awk -F'\t' 'NR == 1 { for (i = 1; i <= NF; i++) \
	  if ($$i == "flag") c = i; next } $$2 == $(FIG2_A) && $$c != "" { printf "%s=%s ", $$1, $$c }' \
	  $(DATA)/fig23-groups.tsv)'" plots/fig3.gp

# --- Fig. 1: 400 dimers, a = d, alpha = 0.95 -----------------------------------------------
$(eval $(call RUN,$(RD)/fig1.db,scenes/paper-fig1.ini,--seed 1))
$(DATA)/fig1.tsv: $(RD)/fig1.db $(SCRIPTS)/fig1data.sh
	$(SCRIPTS)/fig1data.sh $< final > $@
$(OUT)/fig1.png $(OUT)/fig1.svg $(OUT)/fig1.pdf: $(OUT)/fig1.%: $(DATA)/fig1.tsv plots/fig1.gp $(STYLE)
	$(GNUPLOT) -e "in='$<'; out='$@'; title='400 dimers, a = d, α = 0.95, η = $(ETA): final state'" plots/fig1.gp

# --- Fig. 5 and <f>: logged collisions, alpha = 0.98 and 1 (a = d), elastic a/d = FMEAN_A ----
$(eval $(call RUN,$(RD)/fig5-al0.98.db,scenes/paper-fig5.ini,--set dimers.alpha=0.98 --set run.stop_cpd=$(FIG5_CPD) --seed 1))
$(eval $(call RUN,$(RD)/fig5-al1.db,scenes/paper-fig5.ini,--set dimers.alpha=1 --set run.stop_cpd=$(FIG5_CPD) --seed 2))
FMEAN_DBS := $(foreach a,$(filter-out 1,$(FMEAN_A)),$(RD)/fmean-a$(a).db)
$(foreach a,$(filter-out 1,$(FMEAN_A)),$(eval $(call RUN,$(RD)/fmean-a$(a).db,scenes/paper-fig5.ini,\
  --set dimers.alpha=1 --set dimers.a=$(a) --set run.stop_cpd=$(FIG5_CPD) --seed 3)))
$(eval $(call MERGE,$(DATA)/fig5.db,$(RD)/fig5-al0.98.db $(RD)/fig5-al1.db))
$(eval $(call MERGE,$(DATA)/fmean.db,$(RD)/fig5-al0.98.db $(RD)/fig5-al1.db $(FMEAN_DBS)))
$(DATA)/angles.tsv: $(DATA)/fig5.db $(HAFF)
	$(HAFF) angles $< --run 1 -o $@
# the elastic run as one block (its whole log): the bullets of Fig. 5
$(DATA)/angles_elastic.tsv: $(DATA)/fig5.db $(HAFF)
	$(HAFF) angles $< --run 2 -o $@ --block $$(sqlite3 $< \
	  "SELECT count(*) FROM collisions WHERE run = 2 AND kind = 'dimer-dimer'")
$(OUT)/fmean_vs_engine.tsv: $(DATA)/fmean.db $(HAFF) $(SCRIPTS)/fmean_engine.sh
	$(SCRIPTS)/fmean_engine.sh $(HAFF) $< $(MC_SAMPLES) > $@
$(OUT)/fig5.png $(OUT)/fig5.svg $(OUT)/fig5.pdf: $(OUT)/fig5.%: $(DATA)/angles.tsv $(DATA)/angles_elastic.tsv $(OUT)/fmean_vs_engine.tsv plots/fig5.gp $(STYLE)
	$(GNUPLOT) -e "in='$<'; in2='$(DATA)/angles_elastic.tsv'; fm='$(OUT)/fmean_vs_engine.tsv'; ad=1; out='$@'" plots/fig5.gp

# --- Fig. 6: velocity snapshots at [log] velocities_at --------------------------------------
# run 1's snapshots one by one, and the snapshots of FIG6_RUNS runs inside their HCS windows
# pooled (veldist --pool), so that the tails reach |c| = 4-5
$(eval $(call RUN,$(RD)/fig6.db,scenes/paper-fig6.ini,--seed 1))
FIG6_DBS := $(foreach s,$(shell seq 1 $(FIG6_RUNS)),$(RD)/fig6pool-s$(s).db)
$(foreach s,$(shell seq 1 $(FIG6_RUNS)),$(eval $(call RUN,$(RD)/fig6pool-s$(s).db,scenes/paper-fig6-pool.ini,--seed $(s))))
$(eval $(call MERGE,$(DATA)/fig6all.db,$(FIG6_DBS)))
$(DATA)/veldist.tsv: $(RD)/fig6.db $(HAFF)
	$(HAFF) veldist $< --run 1 -o $@
$(DATA)/veldist_pool.tsv: $(DATA)/fig6all.db $(HAFF)
	$(HAFF) veldist $< --pool --bins 50 -o $@
$(DATA)/veldist_stats.tsv: $(RD)/fig6.db $(HAFF)
	$(HAFF) veldist $< --run 1 --stats -o $@
$(OUT)/fig6.png $(OUT)/fig6.svg $(OUT)/fig6.pdf: $(OUT)/fig6.%: $(DATA)/veldist.tsv $(DATA)/veldist_pool.tsv plots/fig6.gp $(STYLE)
	$(GNUPLOT) -e "in='$<'; pool='$(DATA)/veldist_pool.tsv'; out='$@'" plots/fig6.gp

# --- error of D_e against CPU time (issue 5) -------------------------------------------------
err_db = $(RD)/err-a$(ERR_A)-al$(ERR_ALPHA)-c$(1)-s$(2).db
$(foreach c,$(ERR_CPD),$(foreach s,$(ESEEDS),$(eval $(call RUN,$(call err_db,$(c),$(s)),\
  scenes/paper-dimers.ini,--set dimers.count=$(NDIM) --set dimers.a=$(ERR_A) --set \
  dimers.alpha=$(ERR_ALPHA) --set run.stop_cpd=$(c) --seed $(s)))))
$(foreach c,$(ERR_CPD),$(eval $(call MERGE,$(DATA)/err-c$(c).db,$(foreach s,$(ESEEDS),$(call err_db,$(c),$(s))))))
$(DATA)/errcost.tsv: $(foreach c,$(ERR_CPD),$(DATA)/err-c$(c).db) $(HAFF) $(SCRIPTS)/errcost.sh
	$(SCRIPTS)/errcost.sh $(HAFF) $(foreach c,$(ERR_CPD),$(c):$(DATA)/err-c$(c).db) > $@
# the same in the stable box of ERR_NSTABLE dimers
err_s_db = $(RD)/err-n$(ERR_NSTABLE)-a$(ERR_A)-al$(ERR_ALPHA)-c$(1)-s$(2).db
$(foreach c,$(ERR_CPD),$(foreach s,$(ESEEDS),$(eval $(call RUN,$(call err_s_db,$(c),$(s)),\
  scenes/paper-dimers.ini,--set dimers.count=$(ERR_NSTABLE) --set dimers.a=$(ERR_A) --set \
  dimers.alpha=$(ERR_ALPHA) --set run.stop_cpd=$(c) --seed $(s)))))
$(foreach c,$(ERR_CPD),$(eval $(call MERGE,$(DATA)/err-n$(ERR_NSTABLE)-c$(c).db,$(foreach s,$(ESEEDS),$(call err_s_db,$(c),$(s))))))
$(DATA)/errcost-stable.tsv: $(foreach c,$(ERR_CPD),$(DATA)/err-n$(ERR_NSTABLE)-c$(c).db) $(HAFF) $(SCRIPTS)/errcost.sh
	$(SCRIPTS)/errcost.sh $(HAFF) $(foreach c,$(ERR_CPD),$(c):$(DATA)/err-n$(ERR_NSTABLE)-c$(c).db) > $@
$(OUT)/errcost.png $(OUT)/errcost.svg $(OUT)/errcost.pdf: $(OUT)/errcost.%: $(DATA)/errcost.tsv $(DATA)/errcost-stable.tsv plots/errcost.gp $(STYLE)
	$(GNUPLOT) -e "in='$<'; in2='$(DATA)/errcost-stable.tsv'; out='$@'; \
	  title='$(NDIM) dimers (L ≈ L_c)'; title2='$(ERR_NSTABLE) dimers (stable)'; \
	  suptitle='D_e at α = $(ERR_ALPHA), a/d = $(ERR_A), η = $(ETA)'" plots/errcost.gp

# --- hcs: the state measures against cpd below and above the HCS's critical size (issue 15) ---
$(foreach n,$(HCS_STABLE) $(HCS_UNSTABLE),$(eval $(call RUN,$(RD)/hcs-al$(HCS_ALPHA)-n$(n).db,\
  scenes/paper-disks.ini,--set disks.count=$(n) --set disks.alpha=$(HCS_ALPHA) --set \
  run.stop_cpd=$(HCS_CPD) --seed 1)))
$(DATA)/hcs-n%.tsv: $(RD)/hcs-al$(HCS_ALPHA)-n%.db
	sqlite3 -separator $$'\t' $< "SELECT cpd, s_perp, s_par, flow_frac / flow_chaos, count_var, \
	  s_rho FROM samples ORDER BY t" > $@
hcs_label = $(shell awk 'BEGIN { n = $(1); printf "%d disks, α = $(HCS_ALPHA), L = %.0f d", n, sqrt(n * 3.14159265 / 4 / $(ETA)) }')
$(OUT)/hcs.png $(OUT)/hcs.svg $(OUT)/hcs.pdf: $(OUT)/hcs.%: $(DATA)/hcs-n$(HCS_STABLE).tsv $(DATA)/hcs-n$(HCS_UNSTABLE).tsv plots/hcs.gp $(STYLE)
	$(GNUPLOT) -e "stable='$<'; unstable='$(DATA)/hcs-n$(HCS_UNSTABLE).tsv'; out='$@'; \
	  ls='$(call hcs_label,$(HCS_STABLE))'; lu='$(call hcs_label,$(HCS_UNSTABLE))'; \
	  alpha=$(HCS_ALPHA); eta=$(ETA)" plots/hcs.gp

# --- plots/out/README.md: plots/README.md and this build's numbers ---------------------------
$(OUT)/README.md: plots/README.md $(SCRIPTS)/readme.sh $(TABLES) $(DATA)/fits.tsv \
                  $(DATA)/fits-groups.tsv $(DATA)/gap.tsv $(DATA)/gap-fits.tsv \
                  $(DATA)/long-fits.tsv $(DATA)/errcost.tsv $(DATA)/errcost-stable.tsv \
                  $(DATA)/veldist_stats.tsv $(DATA)/config.txt
	$(SCRIPTS)/readme.sh $(OUT) $(DATA) '$(CONFIG)' $(HAFF) > $@

# --- plots/out/index.html: every figure and Tables I-II on one self-contained page -----------
# (plots/scripts/report.py: figures inline as data: URIs, captions with what was run, read from
# the run databases below, the paper's tables beside this build's, provenance)
REPORT_FIGS := fig1 fig2 fig3 fig4 fig5 fig6 hcs errcost shapes species fmean $(FIGS:%=rods-%)
REPORT_DBS  := fig1=$(RD)/fig1.db fig2=$(DATA)/fig23.db fig2=$(DATA)/disks.db fig3=$(DATA)/fig23.db \
  fig5=$(DATA)/fig5.db fig6=$(RD)/fig6.db fig6=$(DATA)/fig6all.db \
  $(foreach n,$(HCS_STABLE) $(HCS_UNSTABLE),hcs=$(RD)/hcs-al$(HCS_ALPHA)-n$(n).db) \
  $(foreach c,$(ERR_CPD),errcost=$(DATA)/err-c$(c).db errcost=$(DATA)/err-n$(ERR_NSTABLE)-c$(c).db) \
  fmean=$(DATA)/tables.db $(foreach m,$(SP_MASSES),$(foreach al,$(SP_ALPHAS),species=$(call sp_db,$(m),$(al)))) \
  $(foreach f,energy collisions,rods-$(f)=$(RODS_DIR)/rods-stochastic.db \
    rods-$(f)=$(RODS_DIR)/rods-constant.db rods-$(f)=$(RODS_DIR)/rods-50.db) \
  rods-damped=$(RODS_DIR)/rods-damped.db rods-damped50=$(RODS_DIR)/rods-damped50.db \
  $(foreach f,density phase local veldist gofr,rods-$(f)=$(RODS_DIR)/rods-stochastic.db)
$(OUT)/index.html: $(REPORT_FIGS:%=$(OUT)/%.png) $(OUT)/table1.tsv $(OUT)/table2.tsv \
                   $(SCRIPTS)/report.py $(DATA)/config.txt $(HAFF)
	$(SCRIPTS)/report.py $(OUT) --version "$$($(HAFF) --version)" --config '$(CONFIG)' \
	  $(REPORT_DBS:%=--db %) $(REPORT_FIGS:%=--png %) -o $@

plots-clean: fmean-clean
	rm -rf $(OUT)
