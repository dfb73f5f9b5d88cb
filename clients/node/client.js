#!/usr/bin/env node
// A Node.js client built from the .proto files alone, loaded at run time: it checks health and
// reads the robot's status and state. It shows that any language with gRPC can drive the robot.
//
//   node clients/node/client.js [host:port]      (default 127.0.0.1:50051, the DecisionServer)
//
// It prints one JSON object and exits 0 when the server answered every call (an error status
// is an answer, and is reported with its code), 1 when the server could not be reached.
'use strict';

const path = require('path');
const grpc = require('@grpc/grpc-js');
const protoLoader = require('@grpc/proto-loader');

const PROTO_ROOT = path.resolve(__dirname, '..', '..', 'protos');
const HEALTH_PROTO = require.resolve('grpc-health-check/proto/health/v1/health.proto');
const LOADER_OPTIONS = { keepCase: true, longs: String, enums: String, defaults: true, oneofs: true };
const DEADLINE_MS = 3000;

function load() {
  const definition = protoLoader.loadSync(
    ['telerobot/v1/proxy_robot.proto', HEALTH_PROTO],
    { ...LOADER_OPTIONS, includeDirs: [PROTO_ROOT] },
  );
  return grpc.loadPackageDefinition(definition);
}

// Calls a unary method and resolves to {ok, reply} or {ok: false, code, details}.
function call(client, method, request) {
  return new Promise((resolve) => {
    const deadline = new Date(Date.now() + DEADLINE_MS);
    client[method](request, { deadline }, (error, reply) => {
      if (error) {
        resolve({ ok: false, code: grpc.status[error.code], details: error.details });
      } else {
        resolve({ ok: true, reply });
      }
    });
  });
}

async function main() {
  const address = process.argv[2] || process.env.TELEROBOT_DECISION_SERVER_ADDRESS || '127.0.0.1:50051';
  const pkg = load();
  const credentials = grpc.credentials.createInsecure();
  const health = new pkg.grpc.health.v1.Health(address, credentials);
  const robot = new pkg.telerobot.v1.ProxyRobot(address, credentials);

  const result = { address, health: {} };
  for (const service of ['', 'telerobot.v1.ProxyRobot']) {
    const answer = await call(health, 'Check', { service });
    if (!answer.ok && answer.code === 'UNAVAILABLE') {
      console.log(JSON.stringify({ address, error: `cannot reach ${address}: ${answer.details}` }));
      process.exit(1);
    }
    result.health[service || '(server)'] = answer.ok ? answer.reply.status : answer.code;
  }
  result.status = await call(robot, 'GetStatus', {});
  result.state = await call(robot, 'GetState', {});
  console.log(JSON.stringify(result, null, 2));
  health.close();
  robot.close();
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
