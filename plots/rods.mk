# The rod paper's figures (Aspelmeier, Giese, Zippelius 1998): make -f plots/rods.mk rods-plots
# Runs scenes/rods-*.ini with $(HAFF) into $(OUT)/data/*.db, extracts TSV with the haff
# rods-* subcommands and draws plots/rods*.gp into $(OUT)/rods-*.png and .svg.
# Default sizes: 1000 rods to t = 1e4 (a few minutes on one core in all); PAPER=1: the
# paper's 10^4 rods to t = 1e5.  A run that ends in collapse (the constant model) is expected.
# Included by plots/plots.mk (`make plots`); the figure rules that write several files are
# grouped targets (&:) so that make -j runs each gnuplot script once.
HAFF ?= bin/haff
OUT  ?= plots/out
D    := $(OUT)/data
ifeq ($(PAPER),1)
BIG  := --set rods.count=10000 --set run.stop_time=1e5
T1   := 14000
T2   := 20000
# the stochastic run's snapshot times at the paper's scale (Figs. 3-8: 14000 and 20000 among them)
VEL  := --set 'log.velocities_at_time=1 2 5 10 20 50 100 200 300 500 700 1000 1500 2000 3000 \
  4000 5000 7000 10000 12000 14000 17000 20000 25000 30000 40000 50000 60000 70000 80000 90000 1e5'
else
BIG  :=
T1   := 1400
T2   := 2000
VEL  :=
endif
RUNS := stochastic constant 50 damped damped50
DBS  := $(RUNS:%=$(D)/rods-%.db)
FIGS := energy collisions density phase local veldist gofr damped damped50 collapse
.PHONY: rods-plots
rods-plots: $(foreach f,$(FIGS),$(OUT)/rods-$(f).png)

$(D)/rods-stochastic.db $(D)/rods-constant.db $(D)/rods-damped.db: $(D)/rods-%.db: scenes/rods-%.ini
	@mkdir -p $(D); rm -f $@
	$(HAFF) run $< -o $@ --quiet $(BIG) $(if $(filter stochastic,$*),$(VEL)) || test $* = constant
$(D)/rods-50.db $(D)/rods-damped50.db: $(D)/rods-%.db: scenes/rods-%.ini
	@mkdir -p $(D); rm -f $@
	$(HAFF) run $< -o $@ --quiet

$(D)/%.energy.tsv: $(D)/%.db
	$(HAFF) rods-energy $< > $@
$(D)/rods-stochastic.density.tsv: $(D)/rods-stochastic.db
	$(HAFF) rods-density $< > $@
$(D)/rods-stochastic.phase1.tsv: $(D)/rods-stochastic.db
	$(HAFF) rods-phase $< --t $(T1) > $@
$(D)/rods-stochastic.phase2.tsv: $(D)/rods-stochastic.db
	$(HAFF) rods-phase $< --t $(T2) > $@
$(D)/rods-stochastic.local.tsv: $(D)/rods-stochastic.db
	$(HAFF) rods-density $< --t 1e9 > $@
$(D)/rods-stochastic.veldist.tsv: $(D)/rods-stochastic.db
	$(HAFF) rods-veldist $< --t $(T1) > $@
$(D)/rods-stochastic.gofr.tsv: $(D)/rods-stochastic.db
	$(HAFF) rods-gofr $< --t $(T1) > $@
$(D)/rods-collapse.tsv: $(HAFF)
	@mkdir -p $(D)
	$(HAFF) rods-collapse --n 4,8,16,32,64 --eps 0.3,0.5,0.7,0.8,0.9,0.95 --seeds 3 --cpd 1000 > $@

ENERGY := $(RUNS:%=$(D)/rods-%.energy.tsv)
$(OUT)/rods-energy.png $(OUT)/rods-collisions.png $(OUT)/rods-damped.png $(OUT)/rods-damped50.png &: $(ENERGY) plots/rods.gp
	gnuplot -e "D='$(D)'; O='$(OUT)'" plots/rods.gp
$(OUT)/rods-density.png $(OUT)/rods-phase.png $(OUT)/rods-local.png $(OUT)/rods-veldist.png $(OUT)/rods-gofr.png &: $(D)/rods-stochastic.density.tsv $(D)/rods-stochastic.phase1.tsv $(D)/rods-stochastic.phase2.tsv $(D)/rods-stochastic.local.tsv $(D)/rods-stochastic.veldist.tsv $(D)/rods-stochastic.gofr.tsv plots/rods-local.gp
	gnuplot -e "D='$(D)'; O='$(OUT)'" plots/rods-local.gp
$(OUT)/rods-collapse.png: $(D)/rods-collapse.tsv plots/rods-collapse.gp
	gnuplot -e "D='$(D)'; O='$(OUT)'" plots/rods-collapse.gp
