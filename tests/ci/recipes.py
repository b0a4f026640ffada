"""The CI recipes the repository carries run here (issue #29, docs/ci.md), so they cannot rot.

  /usr/bin/python3 recipes.py REPO BUILD_DIR WORKDIR

Reads .github/workflows/regression.yml and .gitlab-ci.yml (python3-yaml) and runs their shell
steps in order from REPO, as the CI systems would in their Debian 12 container:

- a GitHub step with `uses:` is the CI system's own action (checkout, cache, upload, publishing
  the report): it is not run, and the test says so; the paths an upload or a report action's
  `with:` names must exist after the steps before it ran (what is uploaded was written);
- `if: always()` steps run after a failed step, steps without `if:` do not; any other condition,
  and any `${{ }}` expression in a script, fails this test (the runner here would not know it);
- the job's variables are the recipe's, except four that point the steps at this machine:
  BUILD_DIR is the build folder ctest runs from (the build step then configures and builds it
  again, finding simbob up to date: no second build of simbob), CMAKE_FLAGS is empty (the flags
  of the recipe would change that build's cache), OUT is a folder under WORKDIR (never the
  repository), and SIMBOB_SCENES is two scenes (the whole list is golden_regression.sh's work).
  GITHUB_STEP_SUMMARY is a file under WORKDIR.

The GitHub workflow runs once with a broken scene in the list: the batch step fails (exit 1),
the always() steps still run, and the summary and the report name the broken scene; the report
validates against Jenkins xunit's junit-10 rules and Ant's strict schema (tests/ci). It runs
again with a build that fails (a `cmake` first in PATH that exits 2): the batch step does not
run, and the summary step must still succeed, saying why there is nothing. The GitLab job runs
with good scenes: every line succeeds, and the report GitLab would read (--junit-extended)
validates against tests/ci/junit.xsd. Both recipes must install git (simbob.revision) and keep
a compiler cache.
"""
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import yaml

REPO, BUILD, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
shutil.rmtree(WORK, ignore_errors=True)  # nothing of an earlier run passes for this one's output
os.makedirs(WORK)
STRICT = ('xunit-junit-10.xsd', 'ant-junit.xsd', 'junit.xsd')
failures = []


def fail(msg):
    print('FAIL: ' + msg)
    failures.append(msg)


def overrides(recipe_env, out, scenes):
    """The recipe's variables, pointed at this machine; the recipe's OUT, to map its paths."""
    env = dict(os.environ)
    env.update({k: str(v) for k, v in recipe_env.items()})
    env.update({'BUILD_DIR': BUILD, 'CMAKE_FLAGS': '', 'OUT': out, 'SIMBOB_SCENES': scenes})
    return env


def run_script(what, script, env):
    if '${{' in script:
        fail(f'{what}: a ${{{{ }}}} expression this runner cannot evaluate: {script!r}')
        return 1
    print(f'--- {what}\n{script}', flush=True)
    p = subprocess.run(['bash', '-e', '-o', 'pipefail', '-c', script], cwd=REPO, env=env)
    print(f'--- {what}: exit {p.returncode}', flush=True)
    return p.returncode


def validate(report, schemas=STRICT):
    for xsd in schemas:
        p = subprocess.run(['xmllint', '--noout', '--schema', os.path.join(REPO, 'tests', 'ci', xsd), report],
                           capture_output=True, text=True)
        if p.returncode != 0:
            fail(f'{report} does not validate against {xsd}: {p.stderr}')


def counts(report):
    r = ET.parse(report).getroot()
    return {k: r.get(k) for k in ('tests', 'failures', 'errors', 'skipped')}


def github(broken_build=False):
    path = os.path.join(REPO, '.github', 'workflows', 'regression.yml')
    wf = yaml.safe_load(open(path))
    (name, job), = wf['jobs'].items()
    if job.get('container') != 'debian:12':
        fail(f'{path}: job {name} runs in {job.get("container")!r}, not debian:12')
    if job.get('defaults', {}).get('run', {}).get('shell') != 'bash':
        fail(f'{path}: the run steps do not say shell: bash (this runner uses bash -e)')
    recipe_out = job['env']['OUT']
    out = os.path.join(WORK, 'github-out-broken-build' if broken_build else 'github-out')
    broken = os.path.join(WORK, 'broken.xml')
    with open(broken, 'w') as f:
        f.write('<?xml version="1.0"?>\n<Simulation>\n  <ComponentList>\n    <RCMobileRigidBody Key="Box" Mass="-1"/>\n'
                '  </ComponentList>\n</Simulation>\n')
    env = overrides({**wf.get('env', {}), **job['env']}, out, f'scenes/chain.xml {broken} scenes/bounce.xml')
    env['GITHUB_STEP_SUMMARY'] = os.path.join(WORK, 'step_summary-broken-build.md' if broken_build else 'step_summary.md')
    open(env['GITHUB_STEP_SUMMARY'], 'w').close()
    if broken_build:
        fake = os.path.join(WORK, 'fake-bin')
        os.makedirs(fake, exist_ok=True)
        with open(os.path.join(fake, 'cmake'), 'w') as f:
            f.write('#!/bin/sh\necho "cmake: a build that fails (tests/ci/recipes.py)" >&2\nexit 2\n')
        os.chmod(os.path.join(fake, 'cmake'), 0o755)
        env['PATH'] = fake + os.pathsep + env['PATH']
    steps_text = '\n'.join(' '.join(str(step.get(k, '')).split()) for step in job['steps'] for k in ('uses', 'run'))
    if not re.search(r'apt-get install .*\bgit\b', steps_text) or 'actions/checkout' not in steps_text or \
            steps_text.index('apt-get install') > steps_text.index('actions/checkout'):
        fail(f'{path}: git is not installed before actions/checkout (simbob.revision would be "unknown")')
    if 'actions/cache' not in steps_text or 'ccache' not in job['env'].get('CMAKE_FLAGS', ''):
        fail(f'{path}: no compiler cache (ccache with actions/cache)')
    failed = False
    exits = {}
    for i, step in enumerate(job['steps']):
        what = f'github step {i + 1} ({step.get("name") or step.get("uses")})'
        cond = step.get('if')
        if cond not in (None, 'always()'):
            fail(f'{what}: condition {cond!r} is not one this runner knows')
            continue
        if failed and cond != 'always()':
            print(f'--- {what}: not run (an earlier step failed, and it has no if: always())')
            continue
        if 'uses' in step:
            print(f'--- {what}: skipped here: {step["uses"]} is the CI system\'s own action')
            if broken_build or step['uses'].startswith(('actions/cache', 'actions/checkout')):
                continue  # nothing to upload after a failed build; a cache is restored, not written
            for key in ('path', 'report_paths'):
                if key in step.get('with', {}):
                    p = str(step['with'][key]).replace(recipe_out, out, 1)
                    if not os.path.exists(p):
                        fail(f'{what}: {key} {step["with"][key]} names nothing the steps wrote ({p})')
            continue
        code = run_script(what, step['run'], {**env, **{k: str(v) for k, v in step.get('env', {}).items()}})
        exits[step.get('name')] = code
        failed = failed or code != 0
    batch = [n for n in exits if n and 'golden' in n]
    if broken_build:
        build = [n for n in exits if n and 'Build' in n]
        if [exits[n] for n in build] != [2] or batch:
            fail(f'the build step should fail (exit 2) and the batch step not run: {exits}')
        if any(code for n, code in exits.items() if n not in build):
            fail(f'a step other than the build failed after the failed build: {exits}')
        summary = open(env['GITHUB_STEP_SUMMARY']).read()
        if 'simbob did not run' not in summary:
            fail(f'the step summary does not say why it is empty:\n{summary}')
        print('ok: the GitHub workflow with a failed build (the summary step did not fail)')
        return
    if [exits[n] for n in batch] != [1]:
        fail(f'the batch step should fail (exit 1) on the broken scene: {exits}')
    if any(code for n, code in exits.items() if n not in batch):
        fail(f'a step other than the batch failed: {exits}')
    report = os.path.join(out, 'junit.xml')
    validate(report)
    if counts(report) != {'tests': '3', 'failures': '0', 'errors': '1', 'skipped': '0'}:
        fail(f'{report}: {counts(report)}')
    summary = open(env['GITHUB_STEP_SUMMARY']).read()
    if not re.search(r'^\| .*broken\.xml \| error \| .*broken\.xml:4: error: ', summary, re.M):
        fail(f'the step summary does not name the broken scene:\n{summary}')
    if not os.path.isfile(os.path.join(out, 'artifacts', 'index.html')):
        fail('no artifacts/index.html to upload')
    print('ok: the GitHub workflow (batch failed as it should, the always() steps ran)')


def gitlab():
    path = os.path.join(REPO, '.gitlab-ci.yml')
    ci = yaml.safe_load(open(path))
    jobs = {k: v for k, v in ci.items() if isinstance(v, dict) and 'script' in v}
    (name, job), = jobs.items()
    if job.get('image') != 'debian:12':
        fail(f'{path}: job {name} runs in {job.get("image")!r}, not debian:12')
    recipe_out = job['variables']['OUT']
    out = os.path.join(WORK, 'gitlab-out')
    env = overrides({**ci.get('variables', {}), **job['variables']}, out, 'scenes/chain.xml scenes/bounce.xml')
    if 'ccache' not in job['variables'].get('CMAKE_FLAGS', '') or '.ccache/' not in job.get('cache', {}).get('paths', []):
        fail(f'{path}: no compiler cache (ccache, cache: paths: .ccache/)')
    lines = job.get('before_script', []) + job['script']
    code = run_script(f'gitlab job {name}', '\n'.join(lines), env)
    if code != 0:
        fail(f'the GitLab job {name} failed (exit {code})')
    art = job.get('artifacts', {})
    if art.get('when') != 'always':
        fail(f'{path}: the artifacts are not kept when the job fails (artifacts: when: always)')
    for p in art.get('paths', []) + [art.get('reports', {}).get('junit', '')]:
        if not p or not os.path.exists(p.replace(recipe_out, out, 1)):
            fail(f'{path}: artifact path {p!r} names nothing the job wrote')
    report = os.path.join(out, 'junit.xml')
    validate(report, ('junit.xsd',))  # --junit-extended: GitLab reads the attachments
    if counts(report) != {'tests': '2', 'failures': '0', 'errors': '0', 'skipped': '0'}:
        fail(f'{report}: {counts(report)}')
    print('ok: the GitLab job')


def documented():
    """docs/ci.md shows the two files as they are."""
    doc = open(os.path.join(REPO, 'docs', 'ci.md')).read()
    for rel in ('.github/workflows/regression.yml', '.gitlab-ci.yml'):
        text = open(os.path.join(REPO, rel)).read()
        if '```yaml\n' + text + '```\n' not in doc:
            fail(f'docs/ci.md does not show {rel} as it is (copy the file into its yaml block)')


def deps_git():
    """scripts/deps.sh run installs git (simbob.revision in the debian:12 recipes)."""
    text = open(os.path.join(REPO, 'scripts', 'deps.sh')).read()
    run = text[text.index('RUN_PACKAGES=('):text.index('TEST_PACKAGES=(')]
    for pkg in ('git', 'ccache'):
        if not re.search(r'^\s+' + pkg + r'\b', run, re.M):
            fail(f'scripts/deps.sh run does not install {pkg}')


def ignored():
    """ci-out/ (the recipes' OUT) and the compiler cache are not committed by accident."""
    lines = open(os.path.join(REPO, '.gitignore')).read().split()
    for p in ('ci-out/', '.ccache/'):
        if p not in lines:
            fail(f'.gitignore does not list {p}')


documented()
deps_git()
ignored()
github()
github(broken_build=True)
gitlab()
if failures:
    sys.exit(f'{len(failures)} failure(s)')
print('all ok')
