#!/usr/bin/env node
// Runs the Khronos glTF validator (npm package gltf-validator, installed by .ci/run
// into .ci/node_modules) on every .gltf / .glb named on the command line. Prints one
// JSON line per file: {"file", "errors", "warnings", "infos", "messages": [first
// errors and warnings]}. Exit status 1 when any file has an error, 2 on bad usage.
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require(path.join(__dirname, 'node_modules', 'gltf-validator'));

async function check(file) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const dir = path.dirname(file);
    const report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 0,
        // External buffers and images are read from the file's own folder.
        externalResourceFunction: (uri) =>
            new Promise((resolve, reject) => {
                fs.readFile(path.join(dir, decodeURIComponent(uri)), (err, data) =>
                    err ? reject(err.toString()) : resolve(new Uint8Array(data)));
            }),
    });
    const issues = report.issues;
    const messages = issues.messages
        .filter((m) => m.severity <= 1)
        .slice(0, 20)
        .map((m) => `${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer || ''}: ${m.message}`);
    return { file, errors: issues.numErrors, warnings: issues.numWarnings, infos: issues.numInfos, messages };
}

(async () => {
    const files = process.argv.slice(2);
    if (files.length === 0) {
        console.error('usage: validate-gltf.js FILE.gltf|FILE.glb ...');
        process.exit(2);
    }
    let failed = false;
    for (const f of files) {
        const r = await check(f);
        failed = failed || r.errors > 0;
        console.log(JSON.stringify(r));
    }
    process.exit(failed ? 1 : 0);
})().catch((e) => {
    console.error(String(e));
    process.exit(1);
});
