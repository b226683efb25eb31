// The activity library (issue #27 §3): ready classroom activities, each a preset with a few
// edits, a question with a prediction, a check the core measures, and teacher notes, in English
// and Chinese. This module is the one place the Activities page, its printed teacher guide, the
// link generator (scripts/activity-links.mjs) and the end-to-end test read them from.
//
// What the check measured on each scene is not written here: scripts/activity-links.mjs runs
// every activity (and its "try next" variant) through the playground's page API and writes the
// links and the measured verdicts to ./measured.js; tests/e2e/activity-library.test.mjs runs
// each link again as a student would and fails when the verdict differs.
//
// A scene edit (`edits`) is plain data applied to the preset's scene JSON by `sceneOf`:
//   { group: 'all' | index, params: {...}, planner: {kind, params}, count }  and  { obstacles: [] }.

/** Topics, in the order the Activities page lists them. */
export const TOPICS = ['flocking', 'swarms', 'pedestrians'];

/** Levels, easiest first. */
export const LEVELS = ['intro', 'intermediate', 'advanced'];

export const ACTIVITIES = [
  {
    id: 'boids-separation',
    topic: 'flocking',
    level: 'intro',
    minutes: 10,
    preset: 'pillars',
    edits: [{ group: 'all', params: { separation_weight: 0 } }],
    check: {
      steps: 1500,
      conditions: [
        { metric: 'arrived_share', op: '>=', value: 0.9 },
        { metric: 'collisions_agent_agent', op: '<=', value: 1000 },
      ],
    },
    expected: 2,
    variant: { edits: [{ group: 'all', params: { separation_weight: 1.5 } }] },
    en: {
      title: 'Boids without separation',
      prompt:
        'Reynolds\' boids steer by three rules: separation (keep apart), alignment (match heading) and cohesion (stay together). Here separation is switched off (weight 0); alignment, cohesion and the seek to the goal are unchanged. The goal: 90 % arrive with at most 1,000 collisions (agent pairs overlapping, counted each step).',
      question: 'Without separation, does the flock still reach the goal without bumping?',
      choices: ['Yes, nothing changes', 'It arrives, with a few bumps', 'It arrives, but agents pile on top of each other'],
      variant: 'Set the separation weight back to 1.5 and run again.',
      expect: 'The flock still reaches the goal quickly, but as one tight clump: the agents overlap, and the collision count runs into the tens of thousands before 90 % arrive.',
      why: 'Alignment and cohesion pull every boid towards its neighbours and nothing pushes back: separation is the only rule that keeps a minimum distance. The pillars are still avoided because the whisker (obstacle avoidance) is a separate force.',
      next: 'Which weight of separation is just enough (try 0.5 and 1)? What happens with separation 5: does the flock still look like a flock? Why does the trail picture stay almost the same while the collision count changes so much?',
    },
    zh: {
      title: '没有分离规则的 Boids',
      prompt:
        'Reynolds 的 boids 按三条规则转向：分离（彼此保持距离）、对齐（与邻居朝向一致）和聚合（留在群体中）。这里把分离关掉了（权重 0）；对齐、聚合和朝目标前进都没有变。目标：90% 到达，且碰撞不超过 1,000 次（每一步重叠的个体对都计数）。',
      question: '没有分离规则，鸟群还能不相撞地到达目标吗？',
      choices: ['能，什么都不变', '能到达，但有少量碰撞', '能到达，但个体挤成一团、相互重叠'],
      variant: '把分离权重改回 1.5，再运行一次。',
      expect: '鸟群仍然很快到达目标，但挤成紧密的一团：个体互相重叠，90% 到达之前碰撞数已达数万次。',
      why: '对齐和聚合把每只 boid 拉向邻居，却没有任何力把它们推开：分离是唯一保持最小距离的规则。柱子仍能避开，因为“触须”（避障）是另一个独立的力。',
      next: '分离权重多大刚好够用（试试 0.5 和 1）？分离权重为 5 时会怎样，还像鸟群吗？为什么轨迹图几乎不变，碰撞数却差这么多？',
    },
  },
  {
    id: 'boids-leader',
    topic: 'flocking',
    level: 'intro',
    minutes: 10,
    preset: 'boids-leader',
    edits: [],
    check: { steps: 500, conditions: [{ metric: 'arrived_share', op: '>=', value: 0.9 }] },
    expected: 1,
    variant: { edits: [{ group: 'all', params: { leader: 'none' } }] },
    en: {
      title: 'Follow the leader',
      prompt:
        'In this flock the first boid is a leader: it walks to the goal at three quarters of full speed, and the others follow a point 30 px behind it instead of seeking the goal themselves. The goal: 90 % of the flock arrive within 500 steps.',
      question: 'Does following a leader get the flock home within 500 steps?',
      choices: ['Yes, sooner than each boid alone', 'No, the leader slows everyone down'],
      variant: 'Set "Leader" to none: every boid seeks the goal itself.',
      expect: 'Missed: at step 500 nobody has arrived yet, the flock is still behind its leader. Less than a hundred steps later it arrives all together.',
      why: 'The followers cannot be faster than the leader they trail, and the leader walks at 0.75 of full speed. Following trades speed for order: the flock stays in one compact group behind one path.',
      next: 'Without a leader the check is met: what does the flock gain, what does it lose (look at the trails and the collisions)? When would a real group prefer to follow a guide?',
    },
    zh: {
      title: '跟随领队',
      prompt:
        '这个鸟群里的第一只 boid 是领队：它以四分之三的全速走向目标，其余的不再自己寻找目标，而是跟随领队身后 30 像素的一点。目标：500 步内鸟群的 90% 到达。',
      question: '跟随领队能让鸟群在 500 步内到家吗？',
      choices: ['能，比各自前进更快', '不能，领队拖慢了大家'],
      variant: '把“领队”设为无：每只 boid 自己寻找目标。',
      expect: '未达成：第 500 步时还没有一只到达，鸟群仍跟在领队后面。不到一百步之后它们一起到达。',
      why: '跟随者不可能比它们跟着的领队更快，而领队只用 0.75 倍全速行走。跟随用速度换来秩序：鸟群沿一条路线保持成紧凑的一团。',
      next: '没有领队时目标达成了：鸟群得到了什么，又失去了什么（看轨迹和碰撞数）？现实中的团体什么时候更愿意跟着向导走？',
    },
  },
  {
    id: 'pso-acceptance',
    topic: 'swarms',
    level: 'intermediate',
    minutes: 15,
    preset: 'pso-static-obstacle',
    edits: [{ group: 'all', params: { acceptance: 'off' } }],
    check: {
      steps: 2000,
      conditions: [
        { metric: 'arrived_share', op: '>=', value: 0.9 },
        { metric: 'penetrations_agent_obstacle', op: '=', value: 0 },
      ],
    },
    expected: 0,
    variant: { edits: [{ group: 'all', params: { acceptance: 'on' } }] },
    en: {
      title: 'PSO: the acceptance test',
      prompt:
        'Each agent is a particle of a particle swarm (PSO): its velocity mixes its own best position and the swarm\'s best. With "acceptance" on, a move that would end inside an obstacle is refused and another direction tried; here acceptance is off. The goal: 90 % arrive with no agent ever inside an obstacle.',
      question: 'With acceptance off, do the particles still keep out of the obstacles?',
      choices: ['No, some go through the obstacles', 'Yes, the obstacle term in the fitness keeps them out'],
      variant: 'Set "acceptance" back to on.',
      expect: 'Missed: agents cut through the obstacle; over a thousand agent-steps are counted inside it and the swarm jams in front of it, so fewer than 90 % arrive by step 2,000.',
      why: 'The obstacle only appears as a penalty in the fitness the swarm minimises; a penalty makes a position worse, it does not forbid it. Inertia and the pull of the best positions carry particles across. The acceptance test is a hard rule applied after the update.',
      next: 'With acceptance on the check is met: what does the rule cost (time to goal, retries)? Raise the obstacle weight with acceptance off: does a larger penalty ever make penetrations zero?',
    },
    zh: {
      title: 'PSO：接受检验',
      prompt:
        '每个个体是粒子群（PSO）中的一个粒子：它的速度综合了自身的最佳位置和群体的最佳位置。开启“接受检验”时，会落入障碍物内部的移动被拒绝，改试别的方向；这里接受检验是关闭的。目标：90% 到达，且始终没有个体进入障碍物。',
      question: '关掉接受检验后，粒子还能不进入障碍物吗？',
      choices: ['不能，有些会穿过障碍物', '能，适应度中的障碍项会让它们留在外面'],
      variant: '把“接受检验”重新打开。',
      expect: '未达成：个体穿过障碍物，累计一千多个“个体·步”在障碍物内部，群体在障碍物前堵住，到第 2,000 步到达的不足 90%。',
      why: '障碍物只作为惩罚项出现在群体最小化的适应度里；惩罚让位置变差，却不禁止它。惯性和最佳位置的吸引会把粒子带过去。接受检验是在更新之后施加的硬性规则。',
      next: '开启接受检验时目标达成：这条规则的代价是什么（到达时间、重试次数）？关闭接受检验时调高障碍权重：更大的惩罚能让穿透数变成零吗？',
    },
  },
  {
    id: 'firefly-queues',
    topic: 'swarms',
    level: 'intermediate',
    minutes: 10,
    preset: 'firefly-migration',
    edits: [],
    check: { steps: 1500, conditions: [{ metric: 'queue_order', op: '>=', value: 0.8 }] },
    expected: 0,
    variant: { edits: [{ group: 'all', params: { beta0: 0 } }] },
    en: {
      title: 'Fireflies form queues',
      prompt:
        'In the firefly algorithm each agent is drawn towards brighter fireflies, and brightness grows as a firefly gets closer to the goal. Queue order measures how many walking fireflies have a brighter one of their group close ahead (0 = scattered, 1 = single files). The goal: queue order reaches 0.8.',
      question: 'Will the fireflies line up in queues on their way to the goal?',
      choices: ['Yes, they form single files', 'No, they stay a scattered cloud'],
      variant: 'Set the attraction β₀ to 0: no firefly is drawn to a brighter one.',
      expect: 'Met within a few hundred steps: the cloud turns into lines, each firefly close behind a brighter one, and the lines thread between the obstacles.',
      why: 'A firefly moves towards the brighter ones it sees, and attraction fades with distance, so the nearest brighter neighbour pulls hardest: each one ends up trailing one neighbour that is nearer the goal. The queue is not programmed, it emerges from that rule.',
      next: 'With β₀ = 0 the check is missed and many fireflies get stuck: what did the queues do for them? Change γ (how fast attraction fades): longer or shorter queues?',
    },
    zh: {
      title: '萤火虫排成队列',
      prompt:
        '在萤火虫算法中，每个个体被更亮的萤火虫吸引，而萤火虫离目标越近就越亮。“排队程度”衡量正在行进的萤火虫中，有多少在前方近处有一只同组且更亮的萤火虫（0 = 分散，1 = 单列）。目标：排队程度达到 0.8。',
      question: '萤火虫在走向目标的路上会排成队列吗？',
      choices: ['会，它们排成单列', '不会，它们保持为分散的一团'],
      variant: '把吸引度 β₀ 设为 0：没有萤火虫会被更亮的同伴吸引。',
      expect: '几百步内达成：分散的一团变成一条条线，每只萤火虫紧跟在一只更亮的后面，队列在障碍物之间穿行。',
      why: '萤火虫朝它看到的更亮个体移动，吸引力随距离衰减，所以最近的更亮邻居拉力最大：每只最终都跟在一只更靠近目标的邻居后面。队列不是编出来的，而是从这条规则中涌现的。',
      next: 'β₀ = 0 时目标未达成，很多萤火虫被困住：队列帮了它们什么？改变 γ（吸引力衰减的快慢）：队列变长还是变短？',
    },
  },
  {
    id: 'igsa-path',
    topic: 'swarms',
    level: 'advanced',
    minutes: 20,
    preset: 'igsa-path-1',
    edits: [],
    check: {
      steps: 2000,
      conditions: [
        { metric: 'arrived_share', op: '>=', value: 0.95 },
        { metric: 'penetrations_agent_obstacle', op: '=', value: 0 },
      ],
    },
    expected: 0,
    variant: { edits: [{ group: 'all', params: { clearance: 0 } }] },
    en: {
      title: 'IGSA plans a path',
      prompt:
        'Before anyone moves, an improved gravitational search algorithm (IGSA) searches for three waypoints that make a short path keeping 12 px away from the obstacles; the group then follows the path. With the Select tool you can drag a waypoint (a handle on the path). The goal: 95 % arrive with no agent inside an obstacle.',
      question: 'Will the planned path bring the whole group through without touching an obstacle?',
      choices: ['Yes, the path keeps clear', 'No, some agents cut a corner into an obstacle'],
      variant: 'Set the clearance to 0 and plan again.',
      expect: 'Met: the path bends around the obstacles and the group walks it without a single penetration.',
      why: 'IGSA scores each candidate path by its length plus a penalty for coming closer than the clearance; the best path of 300 iterations keeps its margin, so agents that spread around it still stay outside.',
      next: 'Drag a waypoint onto an obstacle: what does the check say now? With clearance 0, is the path shorter, and do agents still stay out? Which would you choose for a real crowd?',
    },
    zh: {
      title: 'IGSA 规划路径',
      prompt:
        '在任何人移动之前，改进的引力搜索算法（IGSA）会寻找三个路径点，组成一条离障碍物至少 12 像素的短路径；然后群体沿着这条路径走。用选择工具可以拖动路径点（路径上的手柄）。目标：95% 到达，且没有个体进入障碍物。',
      question: '规划出的路径能让整个群体不碰障碍物地通过吗？',
      choices: ['能，路径保持了距离', '不能，有些个体抄近路进入障碍物'],
      variant: '把间隙设为 0，重新规划。',
      expect: '达成：路径绕开障碍物，群体沿路径行走，没有一次穿透。',
      why: 'IGSA 用路径长度加上“距离小于间隙”的惩罚来给每条候选路径打分；300 次迭代后最好的路径保留了余量，所以在路径两侧散开的个体仍留在障碍物之外。',
      next: '把一个路径点拖到障碍物上：目标检查现在怎么说？间隙为 0 时路径更短吗，个体还能留在外面吗？对真实人群你会选哪一种？',
    },
  },
  {
    id: 'u-trap',
    topic: 'swarms',
    level: 'intermediate',
    minutes: 15,
    preset: 'u-trap',
    edits: [],
    check: { steps: 2000, conditions: [{ metric: 'arrived_share', op: '>=', value: 0.5 }] },
    expected: 1,
    en: {
      title: 'The U-trap: local minima',
      prompt:
        'Four groups start in front of a U-shaped wall that opens towards them, with the goal behind it: PSO, firefly, boids, and boids following a path drawn around the wall. The goal: at least half of all agents arrive within 2,000 steps.',
      question: 'How many groups get out of the U?',
      choices: ['All four', 'Only the group that follows a path', 'None'],
      expect: 'Missed: only "boids on a path" arrives (25 % of all agents); PSO, firefly and plain boids stay in the pocket, many counted as stuck.',
      why: 'The three planners steer by local information: move towards the goal, away from the nearest wall. Inside the U both pulls balance where the goal is straight ahead behind the wall — a local minimum. Only a plan that looks at the whole map (the path) leads out.',
      next: 'Where exactly do the stuck agents wait, and why there? Draw a path for another group, or move the goal: which change frees them? Which planners in this program plan globally?',
    },
    zh: {
      title: 'U 形陷阱：局部极小',
      prompt:
        '四个群体从一道开口朝向它们的 U 形墙前出发，目标在墙的后面：PSO、萤火虫、boids，以及沿着一条绕过墙的路径行走的 boids。目标：2,000 步内至少一半的个体到达。',
      question: '有几个群体能走出 U 形？',
      choices: ['四个都能', '只有沿路径行走的那一组', '一个都不能'],
      expect: '未达成：只有“沿路径的 boids”到达（占全部个体的 25%）；PSO、萤火虫和普通 boids 都留在凹口里，很多被计为“停滞”。',
      why: '这三种规划器只依据局部信息转向：朝目标走、远离最近的墙。在 U 形里面，这两股拉力在“目标就在墙后正前方”的位置相互抵消——这就是局部极小。只有看全局地图的规划（路径）才能带它们出去。',
      next: '停滞的个体究竟停在哪里，为什么在那里？给另一组画一条路径，或者移动目标：哪种改动能解救它们？本程序里哪些规划器做全局规划？',
    },
  },
  {
    id: 'bottleneck-arch',
    topic: 'pedestrians',
    level: 'intermediate',
    minutes: 15,
    preset: 'social-force-bottleneck',
    edits: [],
    check: { steps: 3000, conditions: [{ metric: 'arrived_share', op: '>=', value: 1 }] },
    expected: 0,
    variant: { edits: [{ group: 'all', planner: { kind: 'collision_free_speed', params: {} } }] },
    en: {
      title: 'A bottleneck: the arch at the door',
      prompt:
        'Sixty people leave a room through one door, walking with the social force model (Helbing): each is pushed by its wish to reach the exit and repelled by others and the walls. The goal: everyone is out within 3,000 steps (50 s).',
      question: 'Will all sixty be out within 50 seconds?',
      choices: ['Yes', 'No, the door is too narrow'],
      variant: 'Switch the planner to the collision-free speed model.',
      expect: 'Met, near the limit: a half-circle (arch) of people forms in front of the door and lets them out one or two at a time; the last one leaves after about 44 of the 50 seconds.',
      why: 'The flow through a door is limited by its width, not by how many wait: people arrive faster than the door lets them through, so they pile up in an arch whose shape follows the forces pushing towards the door. Social force bodies may press into each other (counted as collisions).',
      next: 'With the collision-free speed model nobody overlaps, yet the check is missed: why can a model that is "more polite" be slower? Widen the door: does the time halve when the width doubles?',
    },
    zh: {
      title: '瓶颈：门前的拱形',
      prompt:
        '六十个人通过一扇门离开房间，按社会力模型（Helbing）行走：每个人被到达出口的意愿推动，并被他人和墙壁排斥。目标：3,000 步（50 秒）内所有人都离开。',
      question: '六十个人能在 50 秒内全部离开吗？',
      choices: ['能', '不能，门太窄了'],
      variant: '把规划器换成无碰撞速度模型。',
      expect: '达成，但接近时限：门前形成一个半圆（拱形）的人群，一次放出一两个人；最后一个人大约在第 44 秒（共 50 秒）离开。',
      why: '通过门的流量受门宽限制，而不是等待的人数：人们到达的速度快于门放行的速度，于是堆成拱形，形状顺着推向门的合力。社会力模型中的身体可能相互挤压（计为碰撞）。',
      next: '换成无碰撞速度模型后没有人重叠，目标却未达成：为什么“更礼貌”的模型会更慢？把门加宽：宽度加倍时，时间会减半吗？',
    },
  },
  {
    id: 'orca-crossing',
    topic: 'pedestrians',
    level: 'advanced',
    minutes: 15,
    preset: 'orca-crossing',
    edits: [],
    check: {
      steps: 2000,
      conditions: [
        { metric: 'arrived_share', op: '>=', value: 0.9 },
        { metric: 'collisions_agent_agent', op: '=', value: 0 },
      ],
    },
    expected: 0,
    variant: { edits: [{ group: 'all', planner: { kind: 'boids', params: {} } }] },
    en: {
      title: 'ORCA against Boids in a crossing',
      prompt:
        'Four groups of twenty cross a square from all four sides at once. They walk with ORCA (optimal reciprocal collision avoidance): each picks the velocity closest to its wish that cannot collide within the next 2 s, assuming the others do their half. The goal: 90 % arrive without a single collision.',
      question: 'Can eighty people cross through the middle without touching anyone?',
      choices: ['Yes, nobody touches', 'No, the middle is too crowded'],
      variant: 'Switch every group to Boids.',
      expect: 'Met: the groups slow down and weave through each other in the middle; 90 % arrive after about 25 s with zero collisions.',
      why: 'ORCA works with velocities, not forces: it forbids every velocity that would lead to a collision soon and shares the avoiding between both agents. Boids only push away once they are close, which is too late when four streams meet.',
      next: 'With Boids everyone arrives much sooner but with thousands of collisions: which would you trust in an evacuation study, and why? Lower ORCA\'s time horizon to 0.5 s: what changes?',
    },
    zh: {
      title: '十字路口：ORCA 对比 Boids',
      prompt:
        '四组各二十人同时从四个方向穿过一个广场。他们按 ORCA（最优互惠避碰）行走：每个人选择最接近自己意愿、且在接下来 2 秒内不会相撞的速度，并假定对方承担一半的避让。目标：90% 到达，且没有一次碰撞。',
      question: '八十个人能从中间穿过而不碰到任何人吗？',
      choices: ['能，没有人相碰', '不能，中间太拥挤了'],
      variant: '把每个群体都换成 Boids。',
      expect: '达成：各组在中间放慢速度并相互穿插；大约 25 秒后 90% 到达，碰撞为零。',
      why: 'ORCA 处理的是速度而不是力：它禁止所有很快会导致碰撞的速度，并让双方分担避让。Boids 只在靠近之后才相互推开，四股人流相遇时这已经太晚了。',
      next: '换成 Boids 后大家到得快得多，但有数千次碰撞：做疏散研究时你会相信哪一个，为什么？把 ORCA 的时间范围降到 0.5 秒：会有什么变化？',
    },
  },
  {
    id: 'fundamental-diagram',
    topic: 'pedestrians',
    level: 'advanced',
    minutes: 20,
    preset: 'csm-bottleneck',
    edits: [{ obstacles: [] }, { group: 'all', count: 150 }],
    check: {
      steps: 3000,
      conditions: [
        { metric: 'arrived_share', op: '>=', value: 0.5 },
        { metric: 'mean_speed_m_s', op: '>=', value: 1 },
      ],
    },
    expected: 1,
    variant: { edits: [{ obstacles: [] }, { group: 'all', count: 20 }] },
    en: {
      title: 'Crowded means slow: the fundamental diagram',
      prompt:
        'A hundred and fifty people in an open room walk to an exit with the collision-free speed model, each wishing to walk 1.2 m/s. Their speed depends on the gap to the person ahead: the denser the crowd, the shorter the gap. The goal: when half have left, the mean speed is still at least 1 m/s.',
      question: 'Does a crowd of 150 walk as fast as a few people would?',
      choices: ['Yes, everyone keeps their own speed', 'No, the crowd slows everybody down'],
      variant: 'Set the group to 20 people.',
      expect: 'Missed: everybody leaves, but the crowd converging on the exit slows down; the mean speed stays below 1 m/s.',
      why: 'This is the fundamental diagram of pedestrian flow: speed falls as density rises, because each person keeps a time gap to the one ahead. With 20 people the gaps stay long and everyone walks near 1.2 m/s; with 150 they shrink near the exit.',
      next: 'Try 20, 60 and 150 people and write down the mean speed each time: sketch speed against crowd size. The Validation page draws the measured diagram against Weidmann\'s curve: how close is it?',
    },
    zh: {
      title: '拥挤就慢：基本图',
      prompt:
        '一百五十个人在一个开阔的房间里按无碰撞速度模型走向出口，每个人希望以 1.2 米/秒行走。速度取决于与前面一个人的间距：人群越密，间距越短。目标：一半的人离开时，平均速度仍不低于 1 米/秒。',
      question: '150 人的人群走得和几个人一样快吗？',
      choices: ['一样快，每个人保持自己的速度', '不一样，人群让每个人都慢了下来'],
      variant: '把群体改为 20 人。',
      expect: '未达成：所有人都离开了，但向出口汇聚的人群放慢了速度；平均速度一直低于 1 米/秒。',
      why: '这就是行人流的基本图：密度越高速度越低，因为每个人与前面的人保持一个时间间隔。20 人时间距很长，每个人都接近 1.2 米/秒；150 人时出口附近的间距缩短了。',
      next: '分别试 20、60 和 150 人，每次记下平均速度：画出速度随人数变化的草图。验证页面把测得的基本图与 Weidmann 曲线画在一起：它们有多接近？',
    },
  },
];

/** The activity with id `id`, or undefined. */
export function activityById(id) {
  return ACTIVITIES.find((a) => a.id === id);
}

/**
 * `base` (a preset's scene JSON) with `edits` applied and, given `text` (an activity's words in
 * one language), its activity: the scene a link carries. A new object; `base` is left alone.
 */
export function sceneOf(base, edits, activity = null, text = null) {
  const scene = structuredClone(base);
  for (const edit of edits) {
    if (edit.obstacles) scene.obstacles = structuredClone(edit.obstacles);
    if (edit.group === undefined) continue;
    const groups = edit.group === 'all' ? scene.groups : [scene.groups[edit.group]];
    for (const group of groups) {
      if (edit.planner) group.planner = structuredClone(edit.planner);
      if (edit.params) Object.assign(group.planner.params, edit.params);
      if (edit.count !== undefined) group.count = edit.count;
    }
  }
  if (activity && text) {
    scene.name = text.title;
    const prediction = { question: text.question, choices: text.choices };
    if (activity.expected !== undefined) prediction.expected = activity.expected;
    scene.activity = { prompt: text.prompt, prediction, check: structuredClone(activity.check) };
  }
  return scene;
}
