#!/usr/bin/env bash
# Audit items of issue #9 seen through the real binary: clones of clones run with a key for
# every body, and `simbob check` reports every problem of a scene in one pass (a scene that
# failed to load is compiled too), each on its own exact line.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# ---------------------------------------------------------------- clones of clones
# Before: `check` passed and `run` stopped with "duplicate body key 'C1.Root'" (exit 70): the
# clone C2 of the clone C1 gave its bodies C1's keys again.
check "a clone of a clone of a construction checks and runs; every body has its own key"
cat >clones.xml <<'XML'
<Simulation><ComponentList>
<RCConstruction Key="B">
  <Body><RCMobileRigidBody Key="Root"><Pose><RCGlobalCoordinates><Pose Value="0 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
    <Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body>
  <ChildList><RCHingeJoint Key="Arm"><Body><RCMobileRigidBody Key="Link">
    <Pose><RCLocalCoordinates><Pose Value="1 0 0 0 0 0"/></RCLocalCoordinates></Pose>
    <Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body></RCHingeJoint></ChildList>
</RCConstruction>
<RigidBodyClone Key="C1"><Original Value="B"/><Pose><RCGlobalCoordinates><Pose Value="0 1 5 0 0 0"/></RCGlobalCoordinates></Pose></RigidBodyClone>
<RigidBodyClone Key="C2"><Original Value="C1"/><Pose><RCGlobalCoordinates><Pose Value="0 1 10 0 0 0"/></RCGlobalCoordinates></Pose></RigidBodyClone>
</ComponentList></Simulation>
XML
expect_status 0 "$SIMBOB" check clones.xml
expect_match "check summary" "$LAST_ERR" "clones.xml: ok \(6 mobile bodies, 6 geoms, 3 joints\)"
expect_status 0 "$SIMBOB" run clones.xml --duration 0.05 --out clones.csv
read -r samples bodies rows first last <<<"$(csv_summary clones.csv)"
expect_eq "bodies" "$bodies" 6
expect_eq "body keys of the first sample" "$(awk -F, 'NR > 1 && $1 == "0" { print $2 }' clones.csv | paste -sd' ')" \
  "B.Root B.Arm.Link C1.Root C1.Arm.Link C2.Root C2.Arm.Link"

# ---------------------------------------------------------------- one pass
# Before: `check` stopped after loading failed and printed only the unknown geom type (line 5).
check "check reports load and compile errors of a scene in one pass, each at its line"
cat >many.xml <<'XML'
<Simulation><ComponentList>
<RCMobileRigidBody Key="A"><Geom Macro="NoGeom"/></RCMobileRigidBody>
<RCMobileRigidBody Key="B"><Inertia><RCGenericInertia><Inertia Value="1 2 0 2 1 0 0 0 1"/></RCGenericInertia></Inertia></RCMobileRigidBody>
<RCMobileRigidBody Key="C"><Geom><RCSphereGeom/></Geom><Inertia><RCInertiaByGeom><Mass Value="0"/></RCInertiaByGeom></Inertia></RCMobileRigidBody>
<RCMobileRigidBody Key="D"><Geom><RCSphereGeon/></Geom></RCMobileRigidBody>
<RigidBodyClone Key="E"><Original Value="Nobody"/></RigidBodyClone>
</ComponentList></Simulation>
XML
expect_status 65 "$SIMBOB" check many.xml
expect_lines "stdout" "$LAST_OUT" 0
sort "$LAST_ERR" >got.txt
cat >want.txt <<'TXT'
many.xml:2: error: RCMobileRigidBody 'A': RCInertiaByGeom needs a geom with volume on body 'A' (give it a Geom or use RCGenericInertia)
many.xml:3: error: RCGenericInertia 'B.Inertia': parameter 'Inertia' is not positive definite
many.xml:4: error: RCInertiaByGeom 'C.Inertia': parameter 'Mass' must be > 0 (or negative to use Density)
many.xml:5: error: RCMobileRigidBody 'D': unknown component type 'RCSphereGeon' (did you mean 'RCSphereGeom'?)
many.xml:6: error: RigidBodyClone 'E': parameter 'Original' 'Nobody' names no body
TXT
expect_same_file got.txt want.txt

# Before: only the import error was printed (exit 66), the misspelt Original went unseen.
check "a missing import does not hide a clone error elsewhere"
cat >imports.xml <<'XML'
<Simulation><ComponentList>
<RCImportBody Key="M"><File Value="missing.xml"/></RCImportBody>
<RCMobileRigidBody Key="Ball"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody>
<RigidBodyClone Key="E"><Original Value="Bal"/></RigidBodyClone>
</ComponentList></Simulation>
XML
expect_status 66 "$SIMBOB" check imports.xml
expect_lines "stderr" "$LAST_ERR" 2
expect_match "import error" "$LAST_ERR" "^imports.xml:2: error: RCImportBody 'M': cannot read import '.*missing.xml': No such file or directory$"
expect_match "clone error" "$LAST_ERR" \
  "^imports.xml:4: error: RigidBodyClone 'E': parameter 'Original' 'Bal' names no body \(did you mean 'Ball'\?\)$"

say "ok"
