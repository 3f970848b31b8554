# The rod paper's figures (Aspelmeier, Giese, Zippelius 1998): make -f plots/rods.mk rods-plots
# Runs scenes/rods-*.ini with $(HAFF) into $(RODS_DIR)/rods-*.db, extracts TSV with the haff
# rods-* subcommands and draws plots/rods*.gp into $(OUT)/rods-*.png and .svg.
# Default sizes: 1000 rods to t = 1e4 (a few minutes on one core in all); PAPER=1: the
# paper's 10^4 rods to t = 1e5 (the damped ring alone takes 1.5-2 h: docs/rods.md, Speed).  A
# run that ends in collapse (the constant model) is expected.
# Each size has its own folder RODS_DIR (data/rods-default, data/rods-paper), so switching PAPER reruns
# nothing already made; $(D)/rods-size.txt names the folder last used and the figures depend on
# it, so they are redrawn from that folder's data.  A run is finished when its stamp
# $(RODS_DIR)/rods-NAME.ok exists: a run stopped part way (Ctrl-C, SIGTERM, a full disk, a crash)
# leaves its database and no stamp, and the next make resumes it from its last checkpoint
# (`haff resume`) instead of starting again.  RODS_SET adds --set overrides to every run (tests).
# Included by plots/plots.mk (`make plots`); the figure rules that write several files are
# grouped targets (&:) so that make -j runs each gnuplot script once.
HAFF ?= bin/haff
OUT  ?= plots/out
D    := $(OUT)/data
ifeq ($(PAPER),1)
RODS_SIZE := paper
BIG  := --set rods.count=10000 --set run.stop_time=1e5
T1   ?= 14000
T2   ?= 20000
# the stochastic run's snapshot times at the paper's scale (Figs. 3-8: 14000 and 20000 among them)
VEL  := --set 'log.velocities_at_time=1 2 5 10 20 50 100 200 300 500 700 1000 1500 2000 3000 \
  4000 5000 7000 10000 12000 14000 17000 20000 25000 30000 40000 50000 60000 70000 80000 90000 1e5'
else
RODS_SIZE := default
BIG  :=
T1   ?= 1400
T2   ?= 2000
VEL  :=
endif
RODS_SET ?=
RODS_DIR := $(D)/rods-$(RODS_SIZE)
$(shell mkdir -p $(RODS_DIR); echo '$(RODS_DIR)' | cmp -s - $(D)/rods-size.txt || echo '$(RODS_DIR)' > $(D)/rods-size.txt)
RUNS := stochastic constant 50 damped damped50
FIGS := energy collisions density phase local veldist gofr damped damped50 collapse
.PHONY: rods-plots
rods-plots: $(RUNS:%=$(RODS_DIR)/rods-%.ok) $(foreach f,$(FIGS),$(OUT)/rods-$(f).png \
            $(OUT)/rods-$(f).svg $(OUT)/rods-$(f).pdf)

# A run's stamp, made when its database holds the scene's run to its end: done, or collapsed
# for the constant model.  A database newer than the scene whose run was stopped part way
# (interrupted, killed while running, failed) is resumed from its last checkpoint; any other
# is made afresh.  The databases are not targets, so neither .DELETE_ON_ERROR nor an interrupt
# removes hours of a run.  rods-plots names the stamps, so they are not intermediate files: a
# missing stamp is remade (make would leave a missing intermediate alone while the figures are
# newer than what it was made from).
SIZED := stochastic constant damped
STATUS = $$(sqlite3 $$db "SELECT status FROM runs ORDER BY id DESC LIMIT 1" 2>/dev/null)
$(RODS_DIR)/rods-%.ok: scenes/rods-%.ini
	@mkdir -p $(RODS_DIR)
	@db=$(RODS_DIR)/rods-$*.db; end=done; [ $* = constant ] && end=collapsed; \
	if [ -f $$db ] && [ $$db -nt $< ]; then st=$(STATUS); else st=none; fi; \
	case $$st in \
	  $$end) ;; \
	  interrupted|running|failed) echo "$(HAFF) resume $$db"; $(HAFF) resume $$db --quiet ;; \
	  *) rm -f $$db; echo "$(HAFF) run $< -o $$db"; \
	     $(HAFF) run $< -o $$db --quiet $(if $(filter $*,$(SIZED)),$(BIG)) \
	       $(if $(filter stochastic,$*),$(VEL)) $(RODS_SET) ;; \
	esac; \
	st=$(STATUS); [ "$$st" = $$end ] || { echo "$$db: run $$st, not $$end"; exit 1; }
	@touch $@

$(RODS_DIR)/%.energy.tsv: $(RODS_DIR)/%.ok
	$(HAFF) rods-energy $(<:.ok=.db) > $@
$(RODS_DIR)/rods-stochastic.density.tsv: $(RODS_DIR)/rods-stochastic.ok
	$(HAFF) rods-density $(RODS_DIR)/rods-stochastic.db > $@
$(RODS_DIR)/rods-stochastic.phase1.tsv: $(RODS_DIR)/rods-stochastic.ok
	$(HAFF) rods-phase $(RODS_DIR)/rods-stochastic.db --t $(T1) > $@
$(RODS_DIR)/rods-stochastic.phase2.tsv: $(RODS_DIR)/rods-stochastic.ok
	$(HAFF) rods-phase $(RODS_DIR)/rods-stochastic.db --t $(T2) > $@
$(RODS_DIR)/rods-stochastic.local.tsv: $(RODS_DIR)/rods-stochastic.ok
	$(HAFF) rods-density $(RODS_DIR)/rods-stochastic.db --t 1e9 > $@
$(RODS_DIR)/rods-stochastic.veldist.tsv: $(RODS_DIR)/rods-stochastic.ok
	$(HAFF) rods-veldist $(RODS_DIR)/rods-stochastic.db --t $(T1) --gap 0.2 > $@
$(RODS_DIR)/rods-stochastic.gofr.tsv: $(RODS_DIR)/rods-stochastic.ok
	$(HAFF) rods-gofr $(RODS_DIR)/rods-stochastic.db --t $(T1) --range 250 --bins 500 > $@
$(D)/rods-collapse.tsv: $(HAFF)
	@mkdir -p $(D)
	$(HAFF) rods-collapse --n 4,8,16,32,64 --eps 0.3,0.5,0.7,0.8,0.9,0.95 --seeds 3 --cpd 1000 > $@

ENERGY := $(RUNS:%=$(RODS_DIR)/rods-%.energy.tsv)
ROD_E_FIGS := $(foreach f,energy collisions damped damped50,$(foreach e,png svg pdf,$(OUT)/rods-$(f).$(e)))
$(ROD_E_FIGS) &: $(ENERGY) plots/rods.gp plots/style.gp $(D)/rods-size.txt
	gnuplot -e "D='$(RODS_DIR)'; O='$(OUT)'" plots/rods.gp
LOCAL := $(foreach k,density phase1 phase2 local veldist gofr,$(RODS_DIR)/rods-stochastic.$(k).tsv)
ROD_L_FIGS := $(foreach f,density phase local veldist gofr,$(foreach e,png svg pdf,$(OUT)/rods-$(f).$(e)))
$(ROD_L_FIGS) &: $(LOCAL) plots/rods-local.gp plots/style.gp $(D)/rods-size.txt
	gnuplot -e "D='$(RODS_DIR)'; O='$(OUT)'" plots/rods-local.gp
$(OUT)/rods-collapse.png $(OUT)/rods-collapse.svg $(OUT)/rods-collapse.pdf &: $(D)/rods-collapse.tsv plots/rods-collapse.gp plots/style.gp
	gnuplot -e "D='$(D)'; O='$(OUT)'" plots/rods-collapse.gp
